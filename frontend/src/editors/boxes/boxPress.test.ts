// What a press of the box tool starts: only the selected box moves; a press on any other
// object draws (a drag) or selects it (a click), so a bed filling half the photo is not moved
// by someone drawing a pillow on it.
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneObject } from "../../testing/sceneDocuments";
import { type PressContext, startPress } from "./boxPress";

const bed = sceneObject("o0", "bed", [100, 100, 600, 500]);
const pillow = sceneObject("o1", "pillow", [150, 120, 250, 180]);
const context = (over: Partial<PressContext>): PressContext => ({
  selected: null,
  under: undefined,
  shift: false,
  pixelSize: 1,
  width: 800,
  height: 600,
  ...over,
});
const start = (at: [number, number], over: Partial<PressContext>) => startPress(at, context(over));

describe("a press of the box tool", () => {
  it("on an object that is not selected draws, and leaves the selection to the release", () => {
    const { press, select } = start([300, 300], { under: bed as SceneObject });
    expect(press).toMatchObject({ kind: "draw", pick: "o0" });
    expect(select).toBeUndefined();
  });

  it("on nothing draws and drops the selection at once", () => {
    const { press, select } = start([700, 550], { selected: bed });
    expect(press).toMatchObject({ kind: "draw", pick: null });
    expect(select).toBeNull();
  });

  it("inside the selected box moves it, by a handle resizes it", () => {
    expect(start([300, 300], { selected: bed, under: bed }).press).toMatchObject({
      kind: "edit",
      id: "o0",
      grip: "move",
    });
    expect(start([600, 300], { selected: bed, under: bed }).press).toMatchObject({
      kind: "edit",
      grip: "e",
    });
  });

  it("on a small selected box moves it from most of its inside, its handles shrunk to fit", () => {
    const book = sceneObject("o2", "books", [300, 300, 320, 316]);
    // Full-size handles (9 px each way) would cover the whole of this 20 x 16 px box.
    for (const at of [
      [306, 305],
      [314, 311],
      [310, 308],
    ] as [number, number][])
      expect(start(at, { selected: book, under: book }).press).toMatchObject({ grip: "move" });
    expect(start([302, 301], { selected: book, under: book }).press).toMatchObject({ grip: "nw" });
    expect(start([321, 308], { selected: book, under: book }).press).toMatchObject({ grip: "e" });
  });

  it("on another object inside the selected box draws (a click selects that one)", () => {
    const { press } = start([200, 150], { selected: bed, under: pillow });
    expect(press).toMatchObject({ kind: "draw", pick: "o1" });
  });

  it("with Shift always draws, even inside the selected box", () => {
    const { press } = start([300, 300], { selected: bed, shift: true });
    expect(press).toMatchObject({ kind: "draw", pick: null });
  });
});
