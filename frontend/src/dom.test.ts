// Times shown in tables: to the minute, the month named.
import { describe, expect, it } from "vitest";
import { formatShortTime, formatTime } from "./dom";

describe("formatShortTime", () => {
  it("drops the seconds that formatTime keeps", () => {
    const iso = "2026-12-06T16:39:28Z";
    const short = formatShortTime(iso);
    expect(short).not.toMatch(/:28/);
    expect(short).toMatch(/2026/);
    expect(short.length).toBeLessThan(formatTime(iso).length);
  });

  it("gives back what is not a time", () => {
    expect(formatShortTime("soon")).toBe("soon");
  });
});
