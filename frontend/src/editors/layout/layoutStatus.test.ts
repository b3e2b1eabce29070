import { describe, expect, it } from "vitest";
import { roomDoubts } from "./layoutStatus";

describe("doubts about a dragged room", () => {
  it("has none for a room people live in", () => {
    expect(roomDoubts([6.32, 2.64, 5.48], 1.44)).toEqual([]);
    expect(roomDoubts([2.1, 2.4, 1.6], 1.2)).toEqual([]); // a small bathroom
  });

  it("names a low ceiling, the camera nearly touching it, and a narrow room", () => {
    // A ceiling corner dragged 30 px onto the wrong line (the room of the screenshot).
    expect(roomDoubts([3.86, 1.53, 3.39], 1.44)).toEqual([
      "a ceiling 1.53 m high",
      "0.09 m from the camera to the ceiling",
    ]);
    expect(roomDoubts([0.9, 2.5, 4], 1.4)).toEqual(["a room 0.90 m across"]);
    expect(roomDoubts([5, 7.2, 5], 1.4)).toEqual(["a ceiling 7.20 m high"]);
    // The pipeline's room on a showroom photo whose far corner sat on a window's edge.
    expect(roomDoubts([15.97, 2.75, 6.21], 1.24)).toEqual(["a room 15.97 m long"]);
  });
});
