// The masks' colours. By object (the default): one colour per object, different for every
// object of a scene (up to the palette's size) and stable (from the object's id, so it keeps
// its colour across revisions and reloads, and objects added later do not change the colours
// of those already there). By class: one colour per class, its own in every scene unless
// another class of the scene has a colour too near it.
import { NYU40_CLASSES, type SceneObject } from "@holiscene/schema";
import { hslToRgb, type Rgb } from "./rgb";

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
/** The same for classes: a scene holds a handful, so they can keep farther apart (25 degrees
 * left a lamp's purple and a pillow's blue alike). */
const CLASS_NEAR_HUE = 40;

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
 * A palette slot for each key, in the order given: its preferred slot, unless an earlier key
 * has that slot or one of a near hue (the detector's d2 beside the pipeline's o2); then the
 * free slot farthest in hue from every slot given (the lowest of equals). Keys coming later
 * never move earlier ones. Past 32 keys, slots are shared.
 */
function distinctSlots(
  keys: readonly string[],
  preferred: (key: string) => number,
  near = NEAR_HUE,
): Map<string, number> {
  const used = new Set<number>();
  const slots = new Map<string, number>();
  for (const key of keys) {
    let slot = preferred(key);
    if (used.has(slot) || nearestGiven(slot, used) < near) {
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
    slots.set(key, slot);
  }
  return slots;
}

const paletteColours = (slots: Map<string, number>): Map<string, Rgb> =>
  new Map([...slots].map(([key, slot]) => [key, PALETTE[slot] as Rgb]));

/** An id's series and number: "o12" -> ["o", 12]; an id without a number is a series alone. */
function seriesOf(id: string): [string, number] {
  const numbered = /^(.*?)(\d+)$/.exec(id);
  return numbered ? [numbered[1] ?? "", Number(numbered[2])] : [id, -1];
}

/**
 * The ids in the order their colours are chosen: the objects' in document order, with each
 * object a person removed put back where it stood (after the one before it in its numbered
 * series, else before the one after it), so that a removal changes no other object's colour.
 */
function colourOrder(ids: readonly string[], removed: readonly string[]): string[] {
  const order = [...ids];
  const present = new Set(ids);
  const gone = removed.filter((id) => !present.has(id)).map((id) => [id, ...seriesOf(id)] as const);
  gone.sort((a, b) => a[1].localeCompare(b[1]) || a[2] - b[2]);
  for (const [id, series, number] of gone) {
    const sameSeries = order.map(seriesOf).map(([s, n]) => (s === series ? n : null));
    const before = sameSeries.findLastIndex((n) => n !== null && n < number);
    const after = sameSeries.findIndex((n) => n !== null && n > number);
    const at = before >= 0 ? before + 1 : after >= 0 ? after : order.length;
    order.splice(at, 0, id);
  }
  return order;
}

/** Each object's colour, in document order (new objects come last, so they never move others;
 * `removed`: the ids of objects a person removed, which keep their place). */
export function objectColours(
  objects: readonly Pick<SceneObject, "id">[],
  removed: readonly string[] = [],
): Map<string, Rgb> {
  const ids = objects.map((o) => o.id);
  const all = paletteColours(distinctSlots(colourOrder(ids, removed), preferredSlot));
  return new Map(ids.map((id) => [id, all.get(id) as Rgb]));
}

const classIndex = (cls: string) => (NYU40_CLASSES as readonly string[]).indexOf(cls);

/**
 * The colour of each class of a scene. A class prefers the slot of its NYU-40 number, so it
 * looks the same from scene to scene; the classes choose in that order (NYU-40 lists the most
 * common first), so where two are too near in hue (books beside a bookshelf) the later gives way. A class outside the
 * vocabulary (as imported) comes after them, by name.
 */
export function classColours(classes: Iterable<string>): Map<string, Rgb> {
  const order = (cls: string) => {
    const index = classIndex(cls);
    return index < 0 ? NYU40_CLASSES.length : index;
  };
  const unique = [...new Set(classes)].sort((a, b) => order(a) - order(b) || a.localeCompare(b));
  return paletteColours(
    distinctSlots(
      unique,
      (cls) => {
        const index = classIndex(cls);
        return (index < 0 ? idHash(cls) : index) % SLOTS;
      },
      CLASS_NEAR_HUE,
    ),
  );
}

export type Colouring = "object" | "class";

/** The colour of every object's mask, outline and list swatch, by object or by class;
 * `removed`: the objects a person removed (the scene's removed_by_person). */
export function maskColours(
  objects: readonly Pick<SceneObject, "id" | "class">[],
  colouring: Colouring,
  removed: readonly Pick<SceneObject, "id">[] = [],
): Map<string, Rgb> {
  if (colouring === "object")
    return objectColours(
      objects,
      removed.map((o) => o.id),
    );
  const byClass = classColours(objects.map((o) => o.class));
  return new Map(objects.map((o) => [o.id, byClass.get(o.class) as Rgb]));
}
