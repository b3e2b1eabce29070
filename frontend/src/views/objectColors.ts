// One colour per object: different for every object of a scene (up to the palette's size) and
// stable (from the object's id, so it keeps its colour across revisions and reloads, and
// objects added later do not change the colours of those already there).
import type { SceneObject } from "@holiscene/schema";
import { classRgb, hslToRgb, type Rgb } from "./classColors";

const GOLDEN_ANGLE = 137.508;
const LIGHTNESS = [0.55, 0.38];

/** Palette slot k: consecutive slots far apart in hue; mid lightness reads over any photo. */
const PALETTE: readonly Rgb[] = Array.from({ length: 32 }, (_, k) =>
  hslToRgb((k * GOLDEN_ANGLE) % 360, 0.8, LIGHTNESS[k % LIGHTNESS.length] ?? 0.5),
);

/** FNV-1a over the id's characters: a spread-out number for any id. */
function idHash(id: string): number {
  let hash = 0x811c9dc5;
  for (let i = 0; i < id.length; i++) {
    hash ^= id.charCodeAt(i);
    hash = Math.imul(hash, 0x01000193);
  }
  return hash >>> 0;
}

/**
 * An id's preferred palette slot. Ids numbered in a series ("o0", "o1", ... from the pipeline,
 * "d1", "d2", ... from the detector) take consecutive slots, which are far apart in hue.
 */
function preferredSlot(id: string): number {
  const numbered = /^(.*?)(\d+)$/.exec(id);
  if (!numbered) return idHash(id) % PALETTE.length;
  return (idHash(numbered[1] ?? "") + Number(numbered[2])) % PALETTE.length;
}

/**
 * Each object's colour, in document order: its id's slot of the palette, or the next free
 * one when an earlier object has it (new objects come last, so they never move others).
 */
export function objectColours(objects: readonly Pick<SceneObject, "id">[]): Map<string, Rgb> {
  const used = new Set<number>();
  const colours = new Map<string, Rgb>();
  for (const { id } of objects) {
    let slot = preferredSlot(id);
    for (let tries = 0; used.has(slot) && tries < PALETTE.length; tries++) {
      slot = (slot + 1) % PALETTE.length;
    }
    used.add(slot);
    colours.set(id, PALETTE[slot] as Rgb);
  }
  return colours;
}

export type Colouring = "object" | "class";

/** The colour of every object's mask, outline and list swatch, by object or by class. */
export function maskColours(
  objects: readonly Pick<SceneObject, "id" | "class">[],
  colouring: Colouring,
): Map<string, Rgb> {
  if (colouring === "object") return objectColours(objects);
  return new Map(objects.map((o) => [o.id, classRgb(o.class)]));
}
