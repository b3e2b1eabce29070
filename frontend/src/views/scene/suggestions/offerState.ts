// The offers of one detector run: which are still open (not accepted, now objects; not
// rejected; not over an object of their class) and which one is selected.
import type { SceneObject } from "@holiscene/schema";
import type { DetectedBox } from "../../../inference/detectorTensor";
import { type Offer, offersOf, openOffers } from "../detectionOffers";

export class OfferState {
  /** This run's boxes, best first. */
  private offers: Offer[] = [];
  private rejected: Offer[] = [];
  /** The selected offer's key. */
  selected: string | null = null;

  /** `objects` gives the scene's objects now. */
  constructor(private readonly objects: () => readonly SceneObject[]) {}

  /** How many boxes the run found (open or not). */
  get found(): number {
    return this.offers.length;
  }

  /** The offers still open. */
  open(): Offer[] {
    return openOffers(this.offers, this.objects(), this.rejected);
  }

  selectedOffer(): Offer | null {
    return this.open().find((o) => o.key === this.selected) ?? null;
  }

  /** A new run's boxes: all open again, the best one selected. */
  reset(boxes: readonly DetectedBox[]): void {
    this.offers = offersOf(boxes);
    this.rejected = [];
    this.selected = this.open()[0]?.key ?? null;
  }

  reject(chosen: readonly Offer[]): void {
    this.rejected = [...this.rejected, ...chosen];
  }

  /** The selection moves to the first open offer when its own is gone; returns the open ones. */
  keepSelection(): Offer[] {
    const open = this.open();
    if (this.selected && !open.some((o) => o.key === this.selected)) {
      this.selected = open[0]?.key ?? null;
    }
    return open;
  }
}
