// One colour per object: different for every object of a scene (up to the palette's size) and
// stable (from the object's id, so it keeps its colour across revisions and reloads, and
// objects added later do not change the colours of those already there).
import type { SceneObject } from "@holiscene/schema";
import { classRgb, hslToRgb, type Rgb } from "./classColors";

const GOLDEN_ANGLE = 137.508;
const LIGHTNESS = [0.55, 0.38];
const SLOTS = 32;

/** Slot k's hue: consecutive slots far apart. */
const slotHue = (k: number) => (k * GOLDEN_ANGLE) % 360;

/** Palette slot k: consecutive slots far apart in hue; mid lightness reads over any photo. */
const PALETTE: readonly Rgb[] = Array.from({ length: SLOTS }, (_, k) =>
  hslToRgb(slotHue(k), 0.8, LIGHTNESS[k % LIGHTNESS.length] ?? 0.5),
);

/** Two colours nearer in hue read as one (a darker red is still red): a slot this near a
 * colour given already gives way. */
const NEAR_HUE = 25;

function hueDistance(a: number, b: number): number {
  const d = Math.abs(slotHue(a) - slotHue(b));
  return Math.min(d, 360 - d);
}

/** The least hue distance from slot k to the slots given (360 when none is). */
function nearestGiven(k: number, given: ReadonlySet<number>): number {
  let nearest = 360;
  for (const g of given) nearest = Math.min(nearest, hueDistance(k, g));
  return nearest;
}

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
 * Each object's colour, in document order: its id's slot of the palette, unless an earlier
 * object has that slot or one of a near hue (the detector's d2 beside the pipeline's o2);
 * then the free slot farthest in hue from every slot given (the lowest of equals). New
 * objects come last, so they never move others. Past 32 objects, slots are shared.
 */
export function objectColours(objects: readonly Pick<SceneObject, "id">[]): Map<string, Rgb> {
  const used = new Set<number>();
  const colours = new Map<string, Rgb>();
  for (const { id } of objects) {
    let slot = preferredSlot(id);
    if (used.has(slot) || nearestGiven(slot, used) < NEAR_HUE) {
      let best = -1;
      for (let k = 0; k < SLOTS; k++) {
        const distance = used.has(k) ? -1 : nearestGiven(k, used);
        if (distance > best) {
          best = distance;
          slot = k;
        }
      }
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
