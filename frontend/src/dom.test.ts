// Times shown in tables: to the minute, the month named.
import { describe, expect, it } from "vitest";
import { formatShortTime, formatTime } from "./dom";

describe("formatShortTime", () => {
  it("drops the seconds that formatTime keeps, and this year's year", () => {
    const iso = "2026-12-06T16:39:28Z";
    const short = formatShortTime(iso, new Date("2026-12-07T10:00:00Z"));
    expect(short).not.toMatch(/:28/);
    expect(short).not.toMatch(/2026/);
    expect(short).toMatch(/Dec/);
    expect(short.length).toBeLessThan(formatTime(iso).length);
    expect(formatShortTime(iso, new Date("2027-01-02T10:00:00Z"))).toMatch(/2026/);
  });

  it("gives back what is not a time", () => {
    expect(formatShortTime("soon")).toBe("soon");
  });
});
