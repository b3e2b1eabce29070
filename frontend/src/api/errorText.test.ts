import { describe, expect, it } from "vitest";
import { ApiError, errorText } from "./errors";

describe("error texts for people", () => {
  it("say the server could not be reached when no answer came", () => {
    for (const message of ["Failed to fetch", "NetworkError when attempting to fetch resource."]) {
      expect(errorText(new TypeError(message))).toContain("the server could not be reached");
    }
  });

  it("give the API's own message, and anything else as it is", () => {
    expect(errorText(new ApiError(422, "no object 'd3' in this scene", "422"))).toBe(
      "no object 'd3' in this scene",
    );
    expect(errorText(new TypeError("x is undefined"))).toBe("x is undefined");
    expect(errorText("odd")).toBe("odd");
  });
});
