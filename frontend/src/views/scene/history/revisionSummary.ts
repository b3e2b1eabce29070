// A revision's summary as the history lists it. A pipeline or placement run's summary lists
// the stages that ran by their code names ("pipeline: objects_from_detector, intrinsics,
// ..."): the list says how many ran, and their names as people read them are in its tooltip.
import { readableStage } from "../../common/jobProgress";

const STAGE_LISTS = /^(pipeline|objects placed again): ([a-z0-9_]+(?:, [a-z0-9_]+)*)$/;

export interface RevisionSummary {
  text: string;
  /** The stages that ran, as people read them; "" when the summary names none. */
  title: string;
}

export function revisionSummary(summary: string): RevisionSummary {
  const found = STAGE_LISTS.exec(summary);
  if (!found) return { text: summary, title: "" };
  const [, what, names = ""] = found;
  const stages = names.split(", ").map(readableStage);
  const ran = what === "pipeline" ? "the pipeline ran" : "objects placed again";
  return {
    text: `${ran} (${stages.length} ${stages.length === 1 ? "stage" : "stages"})`,
    title: `Stages: ${stages.join(", ")}`,
  };
}
