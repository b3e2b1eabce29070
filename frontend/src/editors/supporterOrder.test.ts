import { describe, expect, it } from "vitest";
import { nearestFirst } from "./supporterOrder";

const box = (id: string, bbox: [number, number, number, number]) => ({ id, bbox });

describe("nearestFirst", () => {
  it("puts the object under a lamp's foot first, then the nearer of the rest", () => {
    const lamp = box("o9", [100, 40, 140, 120]); // its foot: (120, 120)
    const table = box("o12", [60, 110, 260, 220]); // the foot is inside it
    const shelf = box("o2", [300, 20, 400, 220]); // 160 px to the right
    const books = box("o3", [150, 100, 180, 118]); // 30 px to the right, 2 px up
    expect(nearestFirst(lamp, [shelf, books, table]).map((o) => o.id)).toEqual(["o12", "o3", "o2"]);
  });

  it("orders ties by id as people count (o2 before o10)", () => {
    const child = box("o1", [0, 0, 10, 10]);
    const under = [box("o10", [0, 5, 20, 30]), box("o2", [0, 5, 20, 30])];
    expect(nearestFirst(child, under).map((o) => o.id)).toEqual(["o2", "o10"]);
  });
});
