import { describe, expect, it } from "vitest";
import { revisionSummary } from "./revisionSummary";

describe("revisionSummary", () => {
  it("counts the stages of a run and names them as people read them in the tooltip", () => {
    expect(revisionSummary("pipeline: objects_from_detector, masks_grabcut, scene_mesh")).toEqual({
      text: "the pipeline ran (3 stages)",
      title: "Stages: objects from the detector, masks, 3D scene",
    });
    expect(revisionSummary("objects placed again: placement").text).toBe(
      "objects placed again (1 stage)",
    );
  });

  it("leaves other summaries as they are", () => {
    const edit = "o1 on o4 (below)";
    expect(revisionSummary(edit)).toEqual({ text: edit, title: "" });
    expect(revisionSummary("pipeline: rerun by hand")).toEqual({
      text: "pipeline: rerun by hand",
      title: "",
    });
  });
});
