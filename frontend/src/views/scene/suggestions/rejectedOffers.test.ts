// Rejected suggestions are remembered per scene, and nonsense in storage is ignored.
import { describe, expect, it } from "vitest";
import { MemoryStorage } from "../../../testing/memoryStorage";
import { loadRejected, saveRejected } from "./rejectedOffers";

describe("rejected suggestions in storage", () => {
  it("keeps each scene's rejections apart, and forgets them when emptied", () => {
    const storage = new MemoryStorage();
    saveRejected("s1", [{ cls: "chair", bbox: [1, 2, 30, 40] }], storage);
    saveRejected("s2", [{ cls: "lamp", bbox: [5, 5, 9, 9] }], storage);
    expect(loadRejected("s1", storage)).toEqual([{ cls: "chair", bbox: [1, 2, 30, 40] }]);
    saveRejected("s1", [], storage);
    expect(loadRejected("s1", storage)).toEqual([]);
    expect(storage.length).toBe(1);
  });

  it("reads nothing from text that is not a list of boxes", () => {
    const storage = new MemoryStorage();
    storage.setItem("holiscene.rejectedSuggestions.s1", "{not json");
    expect(loadRejected("s1", storage)).toEqual([]);
    storage.setItem(
      "holiscene.rejectedSuggestions.s1",
      JSON.stringify([
        { cls: "sofa", bbox: [1, 2, 3] },
        { cls: "bed", bbox: [0, 0, 5, 5] },
      ]),
    );
    expect(loadRejected("s1", storage)).toEqual([{ cls: "bed", bbox: [0, 0, 5, 5] }]);
  });

  it("works without storage, for the page's life", () => {
    saveRejected("s1", [{ cls: "chair", bbox: [1, 2, 30, 40] }], null);
    expect(loadRejected("s1", null)).toEqual([]);
  });
});
