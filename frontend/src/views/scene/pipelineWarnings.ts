// The pipeline's warnings on the scene page: one line per stage that could not do something
// (its note, marked as a warning in the stored scene), above the photo and the editor. Open the
// first time this browser shows a scene's warnings, unless all are routine; after that folded
// to one line that names the stages, so the photo is not pushed down the page on every visit.
import type { StageRun } from "@holiscene/schema";
import { el } from "../../dom";
import { browserStorage } from "../../state/browserStorage";
import { plural, type SceneSession } from "../../state/sceneSession";
import { readableStage } from "../common/jobProgress";
import { linkObjectIds } from "./objectIdLinks";

export interface PipelineWarning {
  /** What the stage does, in words ("object heights"). */
  stage: string;
  /** The stage's own name ("heights_by_metrology"), as `holiscene infer --stages` takes it. */
  name: string;
  text: string;
  /** A stage that fell back for a few objects, as it does on most real photos (their box for a
   * mask, their class's height): said, but not opened over the photo on a first visit. */
  routine: boolean;
}

/** The stages whose warnings are routine (see PipelineWarning.routine): on 16 of the 17 real
 * photos one of them warns (and on a room with depth, the completion's), and opened they
 * pushed the photo down by 60-100 pixels. */
const ROUTINE_STAGES: ReadonlySet<string> = new Set([
  "masks_grabcut",
  "heights_by_metrology",
  "shape_completion", // a few objects keep their earlier meshes (too few depth points)
]);

/** The stages that find the room layout: their warnings are about the room the pipeline
 * found, not one a person set since. */
const LAYOUT_STAGES: ReadonlySet<string> = new Set(["layout_from_lines", "layout_from_depth"]);

/** Each stage warning of the last pipeline run; `layoutSetByHand`: the room stored now was
 * set by a person after it, which the layout stages' warnings then say. */
export function pipelineWarnings(
  stages: readonly StageRun[],
  layoutSetByHand = false,
): PipelineWarning[] {
  return stages.flatMap((run) => {
    if (!run.warning || !run.note) return [];
    const since =
      layoutSetByHand && LAYOUT_STAGES.has(run.name)
        ? " (the room has since been set by hand)"
        : "";
    return [
      {
        stage: readableStage(run.name),
        name: run.name,
        text: run.note + since,
        routine: ROUTINE_STAGES.has(run.name),
      },
    ];
  });
}

/** The stages that warned, each once, in order ("intrinsics, masks grabcut"). */
export const warnedStages = (warnings: readonly PipelineWarning[]): string =>
  [...new Set(warnings.map((w) => w.stage))].join(", ");

/** The panel (hidden while there is no warning) and how to stop updating it. */
export function pipelineWarningsPanel(session: SceneSession): {
  element: HTMLElement;
  dispose: () => void;
} {
  const title = el("summary", { testid: "pipeline-warnings-title" });
  const seenKey = `holiscene.warningsSeen.${session.sceneId}`;
  let shown: string | null = null; // the warnings listed now
  let shownIds = ""; // the objects they could link to
  const list = el("ul", { className: "pipeline-warnings-list" });
  const element = el(
    "details",
    {
      className: "pipeline-warnings",
      testid: "pipeline-warnings",
      attrs: { "aria-label": "Pipeline warnings" },
    },
    title,
    list,
  );
  const update = () => {
    const { stages, layout } = session.doc.scene;
    const warnings = pipelineWarnings(stages, layout?.source === "manual");
    element.hidden = warnings.length === 0;
    title.textContent = `${plural(warnings.length, "pipeline warning")}: ${warnedStages(warnings)}`;
    const seen = JSON.stringify(warnings);
    const ids = new Set(session.objects.map((o) => o.id));
    const idsNow = [...ids].join(" ");
    // Drawn again when an object comes or goes (a removed one's link goes with it), but
    // opened only for new warnings: the same ones leave the panel as the person set it.
    if (seen === shown && idsNow === shownIds) return;
    const news = seen !== shown;
    shown = seen;
    shownIds = idsNow;
    if (news) {
      const storage = browserStorage();
      // Opened the first time only for a warning worth reading before the photo.
      element.open = warnings.some((w) => !w.routine) && storage?.getItem(seenKey) !== seen;
      if (warnings.length > 0) storage?.setItem(seenKey, seen);
    }
    // An object named in a warning is one click away: the link selects it on the photo.
    const linked = (text: string) =>
      linkObjectIds(
        text,
        ids,
        (id) => session.select(id),
        (id) => `${id} was removed since the pipeline ran`,
      );
    list.replaceChildren(
      ...warnings.map((w) =>
        el(
          "li",
          { testid: "pipeline-warning" },
          el("span", {
            className: "pipeline-warning-stage",
            text: w.stage,
            attrs: { title: `pipeline stage ${w.name}` },
          }),
          el("span", {}, ...linked(w.text)),
        ),
      ),
    );
  };
  update();
  return {
    element,
    dispose: session.subscribe((change) => {
      if (change === "document") update();
    }),
  };
}
