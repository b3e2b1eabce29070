// Which of the detector's boxes the scene page offers as new objects, and the edit that adds
// one (POST /api/scenes/{id}/edits, kind "add_object": the server makes its mask).
import { type AddObject, DETECTOR_MODEL, type SceneObject } from "@holiscene/schema";
import { percentText } from "../../dom";
import { type Box, boxIou, type DetectedBox } from "../../inference/detectorTensor";

/** Boxes that overlap an object (or a rejected offer) of their class more than this are not
 * offered: the object is labelled already. */
export const OVERLAP_IOU = 0.5;

/** A box the detector found, offered as a new object until accepted or rejected. */
export interface Offer {
  /** Unique among the offers of one detection run ("s1", "s2", ...: best first). */
  key: string;
  bbox: Box;
  score: number;
  /** NYU-40. */
  cls: string;
  /** The detector's own class name. */
  sourceClass: string;
  /** A guess: offered only when a person asks for more (suggestions/offerState.ts), pale. */
  faint: boolean;
}

/**
 * The edit that adds an object the detector found: the contract's AddObject without a mask
 * (the server cuts one in the box).
 */
export type AddObjectEdit = Omit<AddObject, "mask"> & { score: number; source: "detector" };

/** The detector's boxes as offers, best first (keys "s1", "s2"...; guesses "g1"...). */
export function offersOf(boxes: readonly DetectedBox[], faint = false): Offer[] {
  return [...boxes]
    .sort((a, b) => b.score - a.score)
    .map((box, i) => ({
      key: `${faint ? "g" : "s"}${i + 1}`,
      bbox: box.bbox,
      score: box.score,
      cls: box.cls,
      sourceClass: box.sourceClass,
      faint,
    }));
}

/** Above this IoU a box is the same place whatever the classes say (the contract's
 * same_place_iou; the detector's NMS is per class, so one thing can come as a "box" and as
 * "books"; an object there is settled: its class is fixed with the picker, not by adding a
 * twin). The pipeline's objects_from_detector stage keeps one box per place the same way. */
export const SAME_PLACE_IOU: number = DETECTOR_MODEL.same_place_iou;

const overlaps = (offer: Offer, other: { cls: string; bbox: readonly number[] }) => {
  const iou = boxIou(offer.bbox, other.bbox);
  return iou > SAME_PLACE_IOU || (other.cls === offer.cls && iou > OVERLAP_IOU);
};

/**
 * The offers still worth showing: none overlapping (IoU > 0.5) an object of the scene of the
 * same class, or a box of the same class the user rejected, or anything (object, rejected
 * box, better offer) at the same place (IoU > 0.7) whatever its class.
 */
export function openOffers(
  offers: readonly Offer[],
  objects: readonly SceneObject[],
  rejected: readonly Pick<Offer, "cls" | "bbox">[] = [],
): Offer[] {
  const taken = [
    ...objects.map((o) => ({ cls: o.class as string, bbox: o.bbox })),
    ...rejected.map((r) => ({ cls: r.cls, bbox: r.bbox })),
  ];
  const open: Offer[] = [];
  for (const offer of offers) {
    // Best first: a lower-scored box of another class at the same place is the same thing.
    const twin = open.some((o) => boxIou(offer.bbox, o.bbox) > SAME_PLACE_IOU);
    if (!twin && !taken.some((t) => overlaps(offer, t))) open.push(offer);
  }
  return open;
}

/** `count` new object ids d1, d2, ... that no object of the scene has. */
export function freshIds(objects: readonly { id: string }[], count: number): string[] {
  const used = new Set(objects.map((o) => o.id));
  const ids: string[] = [];
  for (let n = 1; ids.length < count; n++) {
    const id = `d${n}`;
    if (!used.has(id)) ids.push(id);
  }
  return ids;
}

const round = (value: number, digits: number) => Number(value.toFixed(digits));

/** The edit adding `offer` as object `id` (box to 0.01 px, score to 4 decimals). */
export function addObjectEdit(offer: Offer, id: string): AddObjectEdit {
  return {
    kind: "add_object",
    id,
    class: offer.cls,
    bbox: offer.bbox.map((v) => round(v, 2)) as Box,
    score: Math.min(1, Math.max(0, round(offer.score, 4))),
    source: "detector",
  };
}

/** "chair 87%" */
export const offerLabel = (offer: Offer) => `${offer.cls} ${percentText(offer.score)}`;
