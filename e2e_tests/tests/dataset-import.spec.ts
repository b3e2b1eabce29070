// User story: someone with a labelled dataset (here a COCO export of three photos) imports it
// from the scene list as one .zip, follows the import and reads what came of each photo: a
// photo whose labels are broken is named with the reason and the others are imported; the
// repaired zip then adds only that photo, the others being skipped as already stored.
import { execFileSync } from "node:child_process";
import path from "node:path";
import { expect, test } from "@playwright/test";
import { importZip } from "../helpers/datasetImport";
import { scratchDir } from "../helpers/scratch";
import { screenshotPath } from "../helpers/screenshots";

const REAL = path.resolve(import.meta.dirname, "../../../shared/data/real");
const VENV = path.resolve(import.meta.dirname, "../../.venv/bin");
const holiscene = (...args: string[]) => execFileSync(path.join(VENV, "holiscene"), args);

// Zip the export as it is (coco.zip) and with the first outline of im3d-2.jpg cut to two
// points (broken.zip), as a user would zip the folder.
const ZIP_EXPORT = `
import json, sys, zipfile, pathlib
export, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
data = json.loads((export / "annotations.json").read_text())
def write(name, annotations):
    with zipfile.ZipFile(out / name, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("coco/annotations.json", json.dumps(annotations))
        for image in sorted((export / "images").iterdir()):
            archive.write(image, f"coco/images/{image.name}")
write("coco.zip", data)
broken = next(i["id"] for i in data["images"] if i["file_name"] == "im3d-2.jpg")
next(a for a in data["annotations"] if a["image_id"] == broken)["segmentation"] = [[1, 1, 9, 9]]
write("broken.zip", data)
`;

/** coco.zip and broken.zip of a COCO export (`holiscene export --format coco`). */
function cocoZips(): { coco: string; broken: string } {
  const dir = scratchDir("holiscene-coco-");
  const data = path.join(dir, "data");
  const photos = ["im3d-1", "im3d-2", "t3d-5"].map((name) => path.join(REAL, name));
  holiscene("import", ...photos, "--no-pipeline", "--data-dir", data);
  const exported = path.join(dir, "export");
  holiscene("export", "--format", "coco", "-o", exported, "--data-dir", data);
  execFileSync(path.join(VENV, "python"), ["-c", ZIP_EXPORT, exported, dir]);
  return { coco: path.join(dir, "coco.zip"), broken: path.join(dir, "broken.zip") };
}

test("a COCO zip imports from the scene list, naming the photo that did not", async ({ page }) => {
  const zips = cocoZips();
  await page.goto("/#/");
  const form = page.getByTestId("dataset-import-form");
  await expect(form).toContainText("Import a dataset");

  await importZip(page, zips.broken);
  const summary = page.getByTestId("dataset-import-summary");
  await expect(summary).toContainText(
    "broken.zip: 2 photos imported, 0 skipped as already stored, 1 not imported.",
  );
  const errors = page.getByTestId("dataset-import-errors").locator("li");
  await expect(errors).toHaveCount(1);
  await expect(errors).toContainText("im3d-2.jpg");
  await expect(errors).toContainText("a polygon needs at least 3 points, it has 2");
  const list = page.getByTestId("scene-list");
  await expect(list).toContainText("im3d-1");
  await expect(list).toContainText("t3d-5");
  await expect(list).not.toContainText("im3d-2");
  await form.screenshot({ path: screenshotPath("dataset-import-broken.png") });
  // The form is ready for the next zip: the file cleared, "run the pipeline" left as chosen.
  await expect(page.getByTestId("dataset-import-file")).toHaveValue("");
  await expect(page.getByTestId("dataset-import-pipeline")).not.toBeChecked();

  await importZip(page, zips.coco);
  await expect(summary).toContainText(
    "coco.zip: 1 photo imported, 2 skipped as already stored, 0 not imported.",
  );
  await expect(page.getByTestId("dataset-import-errors")).toHaveCount(0);
  await expect(list).toContainText("im3d-2");
  // Each photo once (the server is shared with other specs: count these rows, not all).
  for (const name of ["im3d-1", "im3d-2", "t3d-5"]) {
    await expect(list.locator("tbody tr", { hasText: name })).toHaveCount(1);
  }
  await page.getByText("Already stored (2)").click();
  await form.screenshot({ path: screenshotPath("dataset-import-again.png") });

  const imported = page.getByTestId("dataset-import-new");
  await expect(imported).toContainText("from im3d-2.jpg");
  await imported.getByRole("link", { name: "im3d-2", exact: true }).click();
  await expect(page.getByTestId("scene-title")).toHaveText("im3d-2");
});

// A synthetic room written as a SUN RGB-D image folder (the backend tests' writer), its first
// outline cut to two clicks, zipped as SUNRGBD/kv1/NYU0042.
const SUN_ZIP = `
import json, sys, zipfile, pathlib
root, room, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
sys.path.insert(0, str(root / "backend"))
from tests.inputs.datasets.sunrgbd_files import write_sun_folder
folder = out / "SUNRGBD" / "kv1" / "NYU0042"
write_sun_folder(room, folder)
index = folder / "annotation2Dfinal" / "index.json"
annotation = json.loads(index.read_text())
first = annotation["frames"][0]["polygon"][0]
first["x"], first["y"] = first["x"][:2], first["y"][:2]
index.write_text(json.dumps(annotation))
with zipfile.ZipFile(out / "sun.zip", "w", zipfile.ZIP_DEFLATED) as archive:
    for path in sorted((out / "SUNRGBD").rglob("*")):
        if path.is_file():
            archive.write(path, path.relative_to(out).as_posix())
`;

test("a SUN RGB-D outline of two clicks is left out with a note beside its photo", async ({
  page,
}) => {
  const dir = scratchDir("holiscene-sun-");
  const rooms = path.join(dir, "rooms");
  holiscene("synth", "--seed", "14", "--count", "1", "--workers", "1", "-o", rooms);
  const root = path.resolve(import.meta.dirname, "../..");
  const room = path.join(rooms, "synth-14");
  execFileSync(path.join(VENV, "python"), ["-c", SUN_ZIP, root, room, dir]);

  await page.goto("/#/");
  await importZip(page, path.join(dir, "sun.zip"));
  const summary = page.getByTestId("dataset-import-summary");
  await expect(summary).toContainText(
    "sun.zip: 1 photo imported (1 with notes), 0 skipped as already stored",
  );
  const photo = page.getByTestId("dataset-import-new").locator("li");
  await expect(photo).toContainText("SUNRGBD/kv1/NYU0042");
  await expect(photo.locator(".import-note")).toHaveText(
    /^polygon 0 of object \d+ \(.+\) has 2 point\(s\): left out$/,
  );
  await page.getByTestId("dataset-import-form").screenshot({
    path: screenshotPath("dataset-import-sun-note.png"),
  });
});

test("a file that is not a zip is refused with the reason", async ({ page }) => {
  await page.goto("/#/");
  await page.getByTestId("dataset-import-file").setInputFiles(path.join(REAL, "t3d-5", "img.jpg"));
  await page.getByTestId("dataset-import-submit").click();
  await expect(page.getByTestId("dataset-import-result")).toContainText(
    "Import failed: the upload is not a .zip file",
  );
});
