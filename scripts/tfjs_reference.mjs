// Runs a TensorFlow.js graph model (pure JavaScript CPU backend) on input tensors written by
// scripts/convert_coco_detector.py and writes its outputs beside them, as the reference the
// converted ONNX model is checked against. Build time only: TensorFlow.js is installed into
// the conversion's scratch folder, never into the project.
//   node tfjs_reference.mjs MODEL_JSON WORK_DIR OUTPUT_NAME[,OUTPUT_NAME...]
// WORK_DIR holds NAME.input.f32 files (float32, the model's input shape); each gets
// NAME.OUTPUT.f32 files.
import { readdirSync, readFileSync, writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import { dirname, join } from "node:path";

const [modelJsonPath, workDir, outputList] = process.argv.slice(2);
const require = createRequire(join(workDir, "..", "package.json"));
const tf = require("@tensorflow/tfjs");

const modelJson = JSON.parse(readFileSync(modelJsonPath, "utf8"));
const weightSpecs = modelJson.weightsManifest.flatMap((group) => group.weights);
const shards = modelJson.weightsManifest.flatMap((group) =>
  group.paths.map((p) => readFileSync(join(dirname(modelJsonPath), p))),
);
const weightData = Buffer.concat(shards);
await tf.setBackend("cpu");
const model = await tf.loadGraphModel(
  tf.io.fromMemory({
    modelTopology: modelJson.modelTopology,
    weightSpecs,
    weightData: weightData.buffer.slice(
      weightData.byteOffset,
      weightData.byteOffset + weightData.byteLength,
    ),
    format: modelJson.format,
    generatedBy: modelJson.generatedBy,
    convertedBy: modelJson.convertedBy,
  }),
);
const inputName = Object.keys(modelJson.signature.inputs)[0];
const inputShape = modelJson.signature.inputs[inputName].tensorShape.dim.map((d) => Number(d.size));
const outputs = outputList.split(",");
for (const file of readdirSync(workDir).filter((f) => f.endsWith(".input.f32"))) {
  const bytes = readFileSync(join(workDir, file));
  const values = new Float32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  const input = tf.tensor(values, inputShape, "float32");
  const results = model.execute({ [inputName]: input }, outputs);
  const list = Array.isArray(results) ? results : [results];
  list.forEach((tensor, i) => {
    const name = file.replace(".input.f32", `.${outputs[i].replaceAll("/", "_")}.f32`);
    writeFileSync(join(workDir, name), Buffer.from(tensor.dataSync().buffer));
    tensor.dispose();
  });
  input.dispose();
  console.log(`reference outputs for ${file}`);
}
