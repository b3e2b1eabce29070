// "Import a dataset": a .zip of a COCO or LabelMe dataset, SUN RGB-D image folders or input
// folders, imported by the server in the background; shows how far it got and, at the end,
// what was imported (with what its labels lost), skipped as already stored, and each photo's
// error.
import type { ImportedPhoto, ImportJob, PhotoError } from "@holiscene/schema";
import { importsApi, pollImport } from "../../api/imports";
import { button, el, failureAlert, labelledField } from "../../dom";
import "./datasetImport.css";

// Up to this many new scenes are listed open; more stay folded behind their count.
const FEW = 10;

const plural = (count: number, one: string, many = `${one}s`) =>
  `${count} ${count === 1 ? one : many}`;

function progressText(job: ImportJob): string {
  const what = job.format ? `${job.format}: ` : "";
  // Imports run one at a time: a queued one may wait for another, or only for its turn.
  if (job.status === "queued") return `${what}queued (imports run one at a time)…`;
  return `${what}${job.done} of ${plural(job.total, "photo")} read`;
}

function sceneLinks(photos: ImportedPhoto[], testid: string): HTMLElement {
  return el(
    "ul",
    { className: "import-list", testid },
    ...photos.map((photo) =>
      el(
        "li",
        {},
        el("a", {
          text: photo.scene_name ?? photo.name,
          attrs: { href: `#/scenes/${encodeURIComponent(photo.scene_id)}` },
        }),
        // The scene's name, and the photo's in the upload where they differ (a download's
        // folder, a file name).
        photo.scene_name && photo.scene_name !== photo.name
          ? el("span", { className: "import-source", text: `from ${photo.name}` })
          : null,
        // What its labels lost on the way in (a support row of an unknown type...).
        ...photo.notes.map((note) => el("span", { className: "import-note", text: note })),
      ),
    ),
  );
}

function errorList(errors: PhotoError[]): HTMLElement {
  return el(
    "ul",
    { className: "import-list import-errors", testid: "dataset-import-errors" },
    ...errors.map((error) =>
      el(
        "li",
        {},
        el("span", { className: "import-error-name", text: error.name }),
        el("span", { className: "import-error-message", text: error.message }),
      ),
    ),
  );
}

/** What the import did, once it ended: counts first, then the lists behind them. */
function summary(job: ImportJob): HTMLElement {
  const noted = job.imported.filter((photo) => photo.notes.length > 0).length;
  const counts = [
    `${plural(job.imported.length, "photo")} imported${noted ? ` (${noted} with notes)` : ""}`,
    `${job.skipped.length} skipped as already stored`,
    `${job.errors.length} not imported`,
  ].join(", ");
  const head =
    job.status === "failed"
      ? el("p", {
          className: "alert alert--error",
          text: `The import stopped: ${job.error ?? "unknown error"}. So far: ${counts}.`,
          attrs: { role: "alert" },
        })
      : el("p", { className: "import-counts", text: `${job.archive}: ${counts}.` });
  const details: HTMLElement[] = [];
  if (job.errors.length > 0) {
    details.push(
      el("h3", { text: `Not imported (${job.errors.length}); nothing of them was stored` }),
      errorList(job.errors),
    );
  }
  if (job.imported.length > 0) {
    details.push(
      el(
        "details",
        { attrs: { open: job.imported.length <= FEW } },
        el("summary", { text: `New scenes (${job.imported.length})` }),
        sceneLinks(job.imported, "dataset-import-new"),
      ),
    );
  }
  if (job.skipped.length > 0) {
    details.push(
      el(
        "details",
        {},
        el("summary", { text: `Already stored (${job.skipped.length})` }),
        sceneLinks(job.skipped, "dataset-import-skipped"),
      ),
    );
  }
  return el("div", { testid: "dataset-import-summary" }, head, ...details);
}

/** The dataset import card; `onScenes` runs whenever new scenes were stored. */
export function datasetImportForm(
  signal: AbortSignal,
  onScenes: () => Promise<void>,
): HTMLFormElement {
  const archive = el("input", {
    testid: "dataset-import-file",
    attrs: { type: "file", name: "archive", accept: ".zip,application/zip", required: true },
  });
  const runPipeline = el("input", {
    testid: "dataset-import-pipeline",
    attrs: { type: "checkbox", name: "run_pipeline", checked: true },
  });
  const submit = button("Import dataset", {
    className: "primary",
    testid: "dataset-import-submit",
    type: "submit",
  });
  const bar = el("progress", { attrs: { max: 1 } });
  const text = el("span", { className: "job-text", testid: "dataset-import-progress-text" });
  const progress = el(
    "div",
    {
      className: "job-progress",
      testid: "dataset-import-progress",
      attrs: { role: "status", "aria-live": "polite", hidden: true },
    },
    bar,
    text,
  );
  const result = el("div", { className: "import-result", testid: "dataset-import-result" });
  const form = el(
    "form",
    { className: "upload-form card", testid: "dataset-import-form" },
    el("h2", { text: "Import a dataset" }),
    el(
      "p",
      { className: "field-hint" },
      "A .zip of a COCO or LabelMe dataset (the JSON with its images), SUN RGB-D image " +
        "folders, or input folders (img.jpg with cam_K.txt, detections.json…), as ",
      el("code", { text: "holiscene export" }),
      " writes them; or plain photos (.jpg, .png), each a scene named after its file. " +
        "A photo imported before with the very same files is skipped, as is a " +
        "scene downloaded from here and not changed since; a downloaded scene edited before " +
        "upload comes in as a new scene. " +
        "NYU Depth v2's .mat is too large " +
        "to upload: import it on the server with ",
      el("code", { text: "holiscene import" }),
      ".",
    ),
    el(
      "div",
      { className: "field-grid" },
      labelledField("Dataset (.zip)", archive),
      el("label", { className: "field-check" }, runPipeline, " Run the pipeline on each photo"),
    ),
    el("div", { className: "form-actions" }, submit),
    progress,
    result,
  );

  let scenesSeen = 0;
  const show = (job: ImportJob) => {
    progress.hidden = false;
    if (job.total > 0 && job.status !== "queued") bar.value = job.done / job.total;
    else bar.removeAttribute("value");
    text.textContent = progressText(job);
    if (job.imported.length > scenesSeen) {
      scenesSeen = job.imported.length;
      void onScenes();
    }
  };

  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const file = archive.files?.[0];
    if (!file) return;
    submit.disabled = true;
    scenesSeen = 0;
    progress.hidden = true;
    result.replaceChildren(el("p", { text: `Uploading ${file.name}…` }));
    try {
      const started = await importsApi.start(file, runPipeline.checked);
      result.replaceChildren();
      const finished = await pollImport(started, show, signal);
      progress.hidden = true;
      result.replaceChildren(summary(finished));
      archive.value = ""; // the zip is done with; the choice of running the pipeline stays
      await onScenes();
      // The new rows above pushed the form down: the summary stays where the person looks.
      result.scrollIntoView({ block: "nearest" });
    } catch (error) {
      if (signal.aborted) return;
      progress.hidden = true;
      result.replaceChildren(failureAlert("Import", error));
    } finally {
      submit.disabled = false;
    }
  });
  return form;
}
