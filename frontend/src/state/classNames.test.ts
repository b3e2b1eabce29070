// The class-name vectors written by the backend (shared_schema/vectors/class_names.json): every
// name keys and stores here as it does on the server.
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/class_names.json?raw";
import { classKey, storedClass } from "./classNames";

interface ClassNameCase {
  name: string;
  key: string;
  stored: string | null;
}

const { cases } = JSON.parse(vectorsText) as { cases: ClassNameCase[] };

describe("class names", () => {
  it("has vectors", () => {
    expect(cases.length).toBeGreaterThan(20);
  });
  it.each(cases)("keys and stores $name as the server does", ({ name, key, stored }) => {
    expect(classKey(name)).toBe(key);
    expect(storedClass(name)).toBe(stored);
  });
});
