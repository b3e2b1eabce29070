// Import a photo (with optional cam_K.txt, detections.json, class_map.json and depth) and follow
// its pipeline job.
import type { SceneSummary } from "@holiscene/schema";
import { api } from "../../api/client";
import { pollJob } from "../../api/jobs";
import { button, el, failureAlert, formatTime, labelledField } from "../../dom";
import { plural } from "../../state/sceneSession";
import { jobProgress } from "../common/jobProgress";
import { pipelineWarnings, warnedStages } from "../scene/pipelineWarnings";
import "./uploadForm.css";

/** Photo names that say nothing of the scene (each dataset folder holds one such photo). */
const GENERIC_PHOTO_NAMES = new Set(["img", "image", "rgb", "photo", "color", "colour", "im"]);
/** "7 Dec, 10:53:12": two photos uploaded a minute apart get names apart. */
const SUGGESTED_TIME: Intl.DateTimeFormatOptions = {
  day: "numeric",
  month: "short",
  hour: "2-digit",
  minute: "2-digit",
  second: "2-digit",
};

function fileField(label: string, name: string, accept: string, hint: string, required = false) {
  const input = el("input", {
    testid: `upload-${name}`,
    attrs: { type: "file", name, accept, required },
  });
  const hintLine = el("span", { className: "field-hint", text: hint });
  if (required) return { input, field: labelledField(label, input, hintLine) };
  // An optional file chosen by mistake (a wrong depth) can be taken off again: a file input
  // alone only swaps one file for another.
  const remove = button("Remove", {
    className: "link-like",
    testid: `upload-${name}-remove`,
    title: `Import without a ${label.toLowerCase()} file`,
    hidden: true,
    onClick: () => {
      input.value = "";
      input.dispatchEvent(new Event("change"));
    },
  });
  input.addEventListener("change", () => {
    remove.hidden = !input.files?.length;
  });
  const row = el("span", { className: "file-row" }, input, remove);
  return { input, field: labelledField(label, row, hintLine) };
}

/** The upload form; `onImported` runs when a scene is created and again when its job ends. */
export function uploadForm(
  signal: AbortSignal,
  onImported: (scene: SceneSummary) => Promise<void>,
) {
  const image = fileField("Photo", "image", "image/*", "JPEG or PNG of an indoor scene", true);
  const camK = fileField("Intrinsics", "cam_k", ".txt,text/plain", "optional cam_K.txt (3×3)");
  const detections = fileField(
    "Detections",
    "detections",
    ".json,application/json",
    "optional detections.json: [{bbox, class}]",
  );
  const classMap = fileField(
    "Class names",
    "class_map",
    ".json,application/json",
    'optional class_map.json: {"your name": "NYU-40 class"}',
  );
  const depth = fileField(
    "Depth",
    "depth",
    ".png,.npy,image/png",
    "optional depth of the same size: 16-bit PNG of millimetres, or .npy of metres",
  );
  const name = el("input", {
    testid: "upload-name",
    attrs: { type: "text", name: "name", placeholder: "defaults to the file name", maxlength: 200 },
  });
  const nameHint = el("span", { className: "field-hint", testid: "upload-name-hint" });
  // Dataset folders name every photo alike (img.jpg, rgb.png): such a name would make a list
  // of scenes all called "img", so the name suggested adds the time of the upload (kept
  // unless the person typed one).
  let suggested = "";
  image.input.addEventListener("change", () => {
    const stem = (image.input.files?.[0]?.name ?? "").replace(/\.[^.]*$/, "");
    const generic = GENERIC_PHOTO_NAMES.has(stem.toLowerCase());
    if (name.value === suggested || name.value === "") {
      suggested = generic
        ? `${stem} of ${formatTime(new Date().toISOString(), SUGGESTED_TIME)}`
        : "";
      name.value = suggested;
    }
    nameHint.textContent = generic
      ? `"${stem}" is what every dataset folder calls its photo: the time is added; change the name if you like.`
      : "";
  });
  const submit = button("Import and run pipeline", {
    className: "primary",
    testid: "upload-submit",
    type: "submit",
  });
  const result = el("div", { className: "upload-result", testid: "upload-result" });
  const form = el(
    "form",
    { className: "upload-form card", testid: "upload-form" },
    el("h2", { text: "New scene" }),
    el(
      "div",
      { className: "field-grid" },
      image.field,
      camK.field,
      detections.field,
      classMap.field,
      depth.field,
      labelledField("Name", name, nameHint),
    ),
    el("div", { className: "form-actions" }, submit),
    result,
  );

  const showResult = () => result.scrollIntoView({ block: "nearest" });

  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    const photo = image.input.files?.[0];
    if (!photo) return;
    submit.disabled = true;
    result.replaceChildren(el("p", { text: `Uploading ${photo.name}…` }));
    try {
      const imported = await api.importScene({
        image: photo,
        camK: camK.input.files?.[0] ?? null,
        detections: detections.input.files?.[0] ?? null,
        classMap: classMap.input.files?.[0] ?? null,
        depth: depth.input.files?.[0] ?? null,
        name: name.value,
      });
      const scene = imported.scene;
      form.reset();
      // The name is optional again; no Remove stays beside an emptied file field.
      for (const field of [image, camK, detections, classMap, depth])
        field.input.dispatchEvent(new Event("change"));
      const link = el("a", {
        text: `Open ${scene.name}`,
        className: "upload-open",
        testid: "upload-open",
        attrs: { href: `#/scenes/${encodeURIComponent(scene.id)}` },
      });
      const progress = jobProgress("upload-job-progress");
      result.replaceChildren(el("p", {}, `Imported ${scene.name}. `, link), progress.element);
      // Not refused (other labels for one photo are fine), but said: a second scene of a
      // photo by mistake doubles an annotator's work.
      const twin = imported.same_photo;
      if (twin)
        result.append(
          el(
            "p",
            { className: "alert alert--warn", testid: "upload-same-photo" },
            "This very photo was imported before, as ",
            el("a", {
              text: twin.name,
              attrs: { href: `#/scenes/${encodeURIComponent(twin.id)}` },
            }),
            `: "${scene.name}" is a second scene of it.`,
          ),
        );
      await onImported(scene);
      // The new row above pushed the form down: its result stays where the person looks.
      showResult();
      if (imported.job) {
        const finished = await pollJob(imported.job, { signal, onUpdate: progress.update });
        void onImported(scene);
        if (finished.status === "succeeded") {
          link.classList.add("is-ready");
          // Enter opens it, unless the person has gone on to something else meanwhile.
          const focused = document.activeElement;
          const waiting = focused === null || focused === document.body || focused === submit;
          if (waiting) link.focus({ preventScroll: true });
        }
        // "Pipeline finished" alone reads as all well on a photo the pipeline could do
        // little with (an all-black one): its warnings are named here, not only on the page.
        if (finished.status === "succeeded") {
          const doc = await api.getScene(scene.id, signal);
          const warnings = pipelineWarnings(doc.scene.stages);
          if (warnings.length > 0) {
            result.append(
              el("p", {
                className: "alert alert--warn",
                testid: "upload-warnings",
                text:
                  `${plural(warnings.length, "pipeline warning")} (${warnedStages(warnings)}): ` +
                  "open the scene to see what to check.",
              }),
            );
            showResult();
          }
        }
      } else {
        progress.element.remove();
      }
    } catch (error) {
      if (signal.aborted) return;
      result.replaceChildren(failureAlert("Import", error));
      showResult(); // the button sits low on the page: the reason must not land below it
    } finally {
      submit.disabled = false;
    }
  });
  return form;
}
