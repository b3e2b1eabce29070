// The offers of one detector run: which are still open (not accepted, now objects; not
// rejected; not over an object of their class) and which one is selected. A run keeps its
// fainter boxes too (down to the class hints' score): a person who asks for them sees them as
// offers, since at a low score the detector finds about twice the real boxes it finds at its
// own threshold, at the cost of many wrong ones (docs/benchmarks.md, "Object detector").
import type { SceneObject } from "@holiscene/schema";
import type { DetectedBox } from "../../../inference/detectorTensor";
import { isStructural } from "../../../state/supportGraph";
import { type Offer, offersOf, openOffers } from "../detectionOffers";
import type { RejectedOffer } from "./rejectedOffers";

export class OfferState {
  /** This run's boxes down to the faintest kept, best first. */
  private offers: Offer[] = [];
  /** Offers below this score stay hidden until `showFainter` (0: every box of the run). */
  private minScore = 0;
  /** The detector's own threshold: the boxes at or above it are its suggestions proper. */
  private threshold = 0;
  /** The selected offer's key. */
  selected: string | null = null;

  /**
   * `objects` gives the scene's objects now; `rejected`, the boxes rejected before (on any run:
   * they stay rejected), and `remember` hears every change to them.
   */
  constructor(
    private readonly objects: () => readonly SceneObject[],
    private rejected: readonly RejectedOffer[] = [],
    private readonly remember: (rejected: readonly RejectedOffer[]) => void = () => {},
  ) {}

  /** How many boxes the run offered (open or not), the fainter ones once shown. */
  get found(): number {
    return this.offers.filter((o) => o.score >= this.minScore).length;
  }

  /** The offers still open. */
  open(): Offer[] {
    return this.openAbove(this.minScore);
  }

  /** The open offers at the detector's threshold or above ("Accept all" takes these: the
   * fainter ones, once shown, are mostly wrong and are accepted one by one). */
  confident(): Offer[] {
    return this.openAbove(this.threshold);
  }

  /** How many more offers would open if the fainter boxes were shown (0 once they are). */
  fainter(): number {
    if (this.minScore === 0) return 0;
    return this.openAbove(0).length - this.open().length;
  }

  /** How many of the shown boxes are left out only because they were rejected before. */
  rejectedHidden(): number {
    return this.openAbove(this.minScore, []).length - this.open().length;
  }

  /** Offer the rejected boxes again (a rejection was a mistake). */
  forgetRejected(): void {
    this.rejected = [];
    this.remember(this.rejected);
  }

  /** Offer the fainter boxes as well; the selection stays where it was. */
  showFainter(): void {
    this.minScore = 0;
  }

  selectedOffer(): Offer | null {
    return this.open().find((o) => o.key === this.selected) ?? null;
  }

  /**
   * A new run's boxes (`boxes` at or above `threshold` are offered, the others down to the
   * faintest kept wait for `showFainter`): open unless rejected before, the best one selected.
   */
  reset(boxes: readonly DetectedBox[], threshold = 0): void {
    this.offers = offersOf(boxes);
    this.minScore = threshold;
    this.threshold = threshold;
    this.selected = this.open()[0]?.key ?? null;
  }

  reject(chosen: readonly Offer[]): void {
    this.rejected = [...this.rejected, ...chosen.map(({ cls, bbox }) => ({ cls, bbox }))];
    this.remember(this.rejected);
  }

  /**
   * Objects gone from `before` to `after` count as rejected boxes: a person who deletes an
   * object (the detector's, accepted or committed by the pipeline) does not want the same box
   * offered back at once, nor on the next run.
   */
  rejectRemoved(before: readonly SceneObject[], after: readonly SceneObject[]): void {
    const kept = new Set(after.map((o) => o.id));
    const removed = before
      .filter((o) => !kept.has(o.id) && !isStructural(o.class))
      .map((o): RejectedOffer => ({ cls: o.class, bbox: [...o.bbox] as RejectedOffer["bbox"] }));
    if (removed.length === 0) return;
    this.rejected = [...this.rejected, ...removed];
    this.remember(this.rejected);
  }

  /** The selection moves to the first open offer when its own is gone; returns the open ones. */
  keepSelection(): Offer[] {
    const open = this.open();
    if (this.selected && !open.some((o) => o.key === this.selected)) {
      this.selected = open[0]?.key ?? null;
    }
    return open;
  }

  private openAbove(score: number, rejected = this.rejected): Offer[] {
    const offers = this.offers.filter((o) => o.score >= score);
    return openOffers(offers, this.objects(), rejected);
  }
}
