// The line above the object list: how many objects need a supporter and how many lack one,
// or, when there is nothing to support, that the objects are still to be added (or that an
// action adding them waits to be retried: "add objects" would then send the person to do it
// twice).
import type { SceneObject } from "@holiscene/schema";
import { plural } from "../state/sceneSession";
import { isStructural } from "../state/supportGraph";

export interface SupportSummary {
  text: string;
  warn: boolean;
}

// True whether or not the detector's boxes are on the photo already (it runs by itself on an
// empty scene): accept the ones you want, or ask for them.
const ADD_OBJECTS =
  "Accept the detector's suggested boxes you want (Detect objects, D, suggests them), or draw each object's box with the Box tool (B)";

export function supportSummary(
  objects: readonly SceneObject[],
  unsupported: number,
  unconfirmed: string | null = null,
): SupportSummary {
  const toSupport = objects.filter((o) => !isStructural(o.class)).length;
  if (toSupport === 0 && unconfirmed) {
    return {
      text: `No objects shown yet: "${unconfirmed}" has no answer from the server. Press Retry under the photo tools (nothing is added twice) or Discard.`,
      warn: true,
    };
  }
  if (objects.length === 0) {
    return { text: `No objects yet. ${ADD_OBJECTS} to add them.`, warn: true };
  }
  if (toSupport === 0) {
    return {
      text: `No objects to support, only the room's walls, floor or ceiling. ${ADD_OBJECTS} to add objects.`,
      warn: true,
    };
  }
  return {
    text:
      `${plural(toSupport, "object")} · ` +
      (unsupported > 0 ? `${unsupported} without a supporter` : "all supported"),
    warn: unsupported > 0,
  };
}
