// Where an object came from, in words, for the object list: boxes given with the photo, the
// object detector (with its score), or a person; and whether people changed it since.
import type { SceneObject } from "@holiscene/schema";
import { percentText } from "../dom";

export interface SourceText {
  /** Short, for the badge: "given", "detector 87%", "by hand", "detector 61% · edited". */
  text: string;
  /** Longer, for the tooltip. */
  title: string;
  kind: "given" | "detector" | "person" | "unknown";
}

type SourceFields = Pick<SceneObject, "source" | "score" | "set_by_person">;

export function objectSource({ source, score, set_by_person }: SourceFields): SourceText {
  const setByPerson = set_by_person ?? [];
  const changed = setByPerson.filter((part) => part !== "object");
  const edited = changed.length > 0 && source !== "manual";
  const editedTitle = edited ? `; a person set its ${changed.join(", ")}` : "";
  const percent = typeof score === "number" ? ` ${percentText(score)}` : "";
  const suffix = edited ? " · edited" : "";
  switch (source) {
    case "given":
      return {
        kind: "given",
        text: `given${suffix}`,
        title: `A box given with the photo${editedTitle}`,
      };
    case "detector":
      return {
        kind: "detector",
        text: `detector${percent}${suffix}`,
        title:
          `Found by the object detector${percent ? ` (score${percent})` : ""}` +
          (setByPerson.includes("object") ? ", accepted by a person" : "") +
          editedTitle,
      };
    case "manual":
      // "by hand", not "person": person is also a class the detector offers.
      return { kind: "person", text: "by hand", title: "Drawn by a person" };
    default:
      return {
        kind: "unknown",
        text: edited ? "edited" : "",
        title: `Stored before sources were recorded${editedTitle}`,
      };
  }
}
