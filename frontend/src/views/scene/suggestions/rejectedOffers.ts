// The suggestions a person rejected on a scene, remembered in this browser: a new detector run
// (the button again, or the page opened another day) does not offer them again. Kept by place
// and class, not by the run's keys, so a rerun or another detector's box at the same place
// stays rejected too (detectionOffers.openOffers compares them so). Without storage (private
// mode) they are kept for the page's life only.
import { browserStorage } from "../../../state/browserStorage";
import type { Offer } from "../detectionOffers";

export type RejectedOffer = Pick<Offer, "cls" | "bbox">;

/** Enough for any photo; the oldest are forgotten first. */
const KEPT = 500;

const storageKey = (sceneId: string) => `holiscene.rejectedSuggestions.${sceneId}`;

const isRejected = (value: unknown): value is RejectedOffer => {
  if (typeof value !== "object" || value === null) return false;
  const { cls, bbox } = value as Record<string, unknown>;
  return (
    typeof cls === "string" &&
    Array.isArray(bbox) &&
    bbox.length === 4 &&
    bbox.every((v) => typeof v === "number" && Number.isFinite(v))
  );
};

/** The rejections stored for the scene (none when storage is missing or holds nonsense). */
export function loadRejected(
  sceneId: string,
  storage: Storage | null = browserStorage(),
): RejectedOffer[] {
  const text = storage?.getItem(storageKey(sceneId));
  if (!text) return [];
  try {
    const stored: unknown = JSON.parse(text);
    return Array.isArray(stored) ? stored.filter(isRejected) : [];
  } catch {
    return [];
  }
}

/** Store the scene's rejections (storage full or refused: they last for this page only). */
export function saveRejected(
  sceneId: string,
  rejected: readonly RejectedOffer[],
  storage: Storage | null = browserStorage(),
): void {
  const kept = rejected.slice(-KEPT).map(({ cls, bbox }) => ({ cls, bbox }));
  try {
    if (kept.length === 0) storage?.removeItem(storageKey(sceneId));
    else storage?.setItem(storageKey(sceneId), JSON.stringify(kept));
  } catch {
    // Quota or private mode: the rejections still hold until the page closes.
  }
}
