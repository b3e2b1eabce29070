// Generate ts/contract.ts from jsonschema/contract.schema.json (written by
// `python -m holiscene_schema.export`). With --check, fail when the committed file is stale.
import { readFile, writeFile } from "node:fs/promises";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { compile } from "json-schema-to-typescript";

const here = dirname(fileURLToPath(import.meta.url));
const schemaPath = join(here, "..", "jsonschema", "contract.schema.json");
const outPath = join(here, "contract.ts");
const vocabularyPath = join(here, "..", "jsonschema", "vocabulary.json");
const vocabularyOutPath = join(here, "vocabulary.ts");

const schema = JSON.parse(await readFile(schemaPath, "utf8"));
// Pydantic titles every field; without this each field would become a named alias type.
const dropFieldTitles = (node, isDefinition) => {
  if (Array.isArray(node)) {
    for (const item of node) dropFieldTitles(item, false);
  } else if (node && typeof node === "object") {
    if (!isDefinition) delete node.title;
    for (const [key, value] of Object.entries(node)) {
      if (key === "$defs") {
        for (const def of Object.values(value)) dropFieldTitles(def, true);
      } else if (key !== "enum" && key !== "const") {
        dropFieldTitles(value, false);
      }
    }
  }
};
dropFieldTitles(schema, true);
// The bundle has only $defs; expose each as a property so every type is declared once.
schema.type = "object";
schema.additionalProperties = false;
schema.properties = Object.fromEntries(
  Object.keys(schema.$defs).map((name) => [name, { $ref: `#/$defs/${name}` }]),
);
const generated = await compile(schema, "HoliSceneContract", {
  bannerComment:
    "// Generated from shared_schema/jsonschema/contract.schema.json by ts/generate.mjs.\n// Do not edit: change the pydantic models and run `make schema`.",
  additionalProperties: false,
  unreachableDefinitions: true,
  format: false,
  style: { singleQuote: false },
});

const vocabulary = JSON.parse(await readFile(vocabularyPath, "utf8"));
const vocabularyTs = [
  "// Generated from shared_schema/jsonschema/vocabulary.json by ts/generate.mjs. Do not edit.",
  `export const NYU40_CLASSES = ${JSON.stringify(vocabulary.nyu40_classes)} as const;`,
  `export const CLASS_ALIASES = ${JSON.stringify(vocabulary.class_aliases)} as const;`,
  `export const CLASS_WORDS = ${JSON.stringify(vocabulary.class_words)} as const;`,
  `export const STRUCTURAL_SUPPORTERS = ${JSON.stringify(vocabulary.structural_supporters)} as const;`,
  `export const SUPPORT_TYPES = ${JSON.stringify(vocabulary.support_types)} as const;`,
  "/** The one support type each part of the room holds objects up by. */",
  `export const STRUCTURAL_SUPPORT_TYPES: Readonly<Record<string, "below" | "behind">> = ${JSON.stringify(vocabulary.structural_support_types)};`,
  `export const RELATION_MODEL = ${JSON.stringify(vocabulary.relation_model)} as const;`,
  `export const DETECTOR_MODEL = ${JSON.stringify(vocabulary.detector_model)} as const;`,
  `export const SUPPORT_GEOMETRY = ${JSON.stringify(vocabulary.support_geometry)} as const;`,
  `export const RETRAINING = ${JSON.stringify(vocabulary.retraining)} as const;`,
  "",
].join("\n");

const outputs = [
  [outPath, generated],
  [vocabularyOutPath, vocabularyTs],
];
if (process.argv.includes("--check")) {
  for (const [path, text] of outputs) {
    const current = await readFile(path, "utf8").catch(() => "");
    if (current !== text) {
      console.error(`${path} is stale: run \`make schema\``);
      process.exit(1);
    }
  }
  console.log("shared_schema/ts is up to date");
} else {
  for (const [path, text] of outputs) await writeFile(path, text);
}
