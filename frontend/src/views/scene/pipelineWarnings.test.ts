// Only the notes the pipeline marked as warnings are listed, each with its stage.
import type { StageRun } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { pipelineWarnings } from "./pipelineWarnings";

const run = (name: string, note: string | null, warning: boolean): StageRun => ({
  name,
  seconds: 0.1,
  note,
  warning,
  model: null,
});

describe("pipeline warnings", () => {
  it("lists each warning with its stage and leaves plain notes out", () => {
    const stages = [
      run("objects_from_detections", "no detections.json was given", true),
      run("intrinsics", null, false),
      run("layout_from_lines", "scale from camera height", false),
      run("heights_by_metrology", "class prior for 1: o2 (measured 9.00 m)", true),
    ];
    expect(pipelineWarnings(stages)).toEqual([
      {
        stage: "objects from the given boxes",
        name: "objects_from_detections",
        text: "no detections.json was given",
        routine: false,
      },
      // A few objects' fallback, as on most real photos: routine (not opened over the photo).
      {
        stage: "object heights",
        name: "heights_by_metrology",
        text: "class prior for 1: o2 (measured 9.00 m)",
        routine: true,
      },
    ]);
  });

  it("says when the room the layout stage warned about was set by hand since", () => {
    const stages = [
      run("layout_from_lines", "too few vertical lines: pitch, roll and layout unknown", true),
      run("placement", "camera pitch, roll or floor unknown: no 3D boxes", true),
    ];
    expect(pipelineWarnings(stages, true).map((w) => w.text)).toEqual([
      "too few vertical lines: pitch, roll and layout unknown (the room has since been set by hand)",
      "camera pitch, roll or floor unknown: no 3D boxes",
    ]);
    expect(pipelineWarnings(stages)[0]?.text).toBe(
      "too few vertical lines: pitch, roll and layout unknown",
    );
  });

  it("has none for a scene without stages", () => {
    expect(pipelineWarnings([])).toEqual([]);
  });
});
