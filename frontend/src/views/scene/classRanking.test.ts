// The class picker's list: NYU-40 classes and aliases matched the server's way, whole names
// before starts before word starts before the rest, the most used first among equals.
import { NYU40_CLASSES } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { CLASS_OPTIONS, rankClasses } from "./classRanking";

const names = (query: string, uses = new Map<string, number>(), limit = 12) =>
  rankClasses(query, uses, limit).map((o) => o.name);

describe("rankClasses", () => {
  it("offers every NYU-40 class but the room's own structure, and the aliases", () => {
    const classes = new Set(CLASS_OPTIONS.filter((o) => o.name === o.cls).map((o) => o.name));
    expect(classes.size).toBe(NYU40_CLASSES.length - 3);
    expect(classes.has("wall")).toBe(false);
    expect(CLASS_OPTIONS).toContainEqual({ name: "nightstand", cls: "night_stand" });
    // night_stand is its own alias: listed once.
    expect(CLASS_OPTIONS.filter((o) => o.name === "night_stand")).toHaveLength(1);
  });

  it("ranks the whole name, then its start, then a word's start, then anywhere", () => {
    expect(names("box")[0]).toBe("box");
    const tab = names("tab", new Map(), 100);
    expect(tab[0]).toBe("table"); // the class, then the aliases that start so
    expect(tab.slice(1, 4)).toEqual(["table_cloth", "table_lamp", "tablecloth"]);
    expect(tab.slice(2, -1).every((n) => n.split("_").some((w) => w.startsWith("tab")))).toBe(true);
    expect(tab.slice(2, -1)).toContain("coffee_table");
    expect(tab.at(-1)).toBe("endtable"); // "tab" inside a word comes last
    expect(names("stand")).toEqual(["stand", "night_stand", "tv_stand", "nightstand"]);
    expect(names("Night Stand")[0]).toBe("night_stand");
    expect(names("zzz")).toEqual([]);
  });

  it("offers the class a free name resolves to, as the import would store it", () => {
    expect(names("chiar")[0]).toBe("chair"); // a typo
    expect(names("wooden chair")[0]).toBe("chair"); // the head noun
    expect(names("book shelves")[0]).toBe("bookshelf"); // the joined form
    expect(names("lamp on table")[0]).toBe("lamp"); // what is on the table
    expect(names("stand")[0]).toBe("stand"); // an alias is offered as itself
    expect(names("cable")).toEqual([]); // no class: a letter typed for another is not fixed
  });

  it("puts the most used first, among equal matches and with nothing typed", () => {
    const uses = new Map([
      ["chair", 5],
      ["lamp", 2],
    ]);
    expect(names("", uses, 3)).toEqual(["chair", "lamp", "cabinet"]);
    expect(names("c", uses, 3)).toEqual(["chair", "cabinet", "counter"]);
    // Aliases of a used class rank with it, but never above a shorter form of themselves.
    expect(names("s", new Map([["chair", 3]]), 3)).toEqual(["seat", "sofa", "sofa_chair"]);
    expect(names("sof", new Map([["chair", 9]]), 2)).toEqual(["sofa", "sofa_chair"]);
  });

  it("puts the classes the detector saw at the box after the match, before the most used", () => {
    const uses = new Map([["chair", 5]]);
    expect(rankClasses("", uses, 3, ["lamp", "desk"]).map((o) => o.name)).toEqual([
      "lamp",
      "desk",
      "chair",
    ]);
    // Typing still decides first: a hinted class that does not match is not listed, but an
    // alias of it that matches is, with the hint's rank.
    const typed = rankClasses("b", uses, 100, ["lamp", "books"]).map((o) => o.name);
    expect(typed).not.toContain("lamp");
    expect(typed.slice(0, 2)).toEqual(["bedside_lamp", "books"]);
  });
});
