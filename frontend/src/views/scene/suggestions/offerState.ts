// The offers of one detector run: which are still open (not accepted, now objects; not
// rejected; not over an object of their class) and which one is selected. A run keeps its
// fainter boxes too (down to the class hints' score): a person who asks for them sees them as
// offers, since at a low score the detector finds about twice the real boxes it finds at its
// own threshold, at the cost of many wrong ones (docs/benchmarks.md, "Object detector").
import type { SceneObject } from "@holiscene/schema";
import type { DetectedBox } from "../../../inference/detectorTensor";
import { type Offer, offersOf, openOffers } from "../detectionOffers";
import type { RejectedOffer } from "./rejectedOffers";

const removedKey = ({ cls, bbox }: RejectedOffer) => JSON.stringify([cls, bbox]);

export class OfferState {
  /** This run's boxes down to the faintest kept, best first. */
  private offers: Offer[] = [];
  /** Offers below this score stay hidden until `showFainter` (0: every box of the run). */
  private minScore = 0;
  /** The detector's own threshold: the boxes at or above it are its suggestions proper. */
  private threshold = 0;
  /** The selected offer's key. */
  selected: string | null = null;

  /** The removed objects' boxes "Offer rejected again" brought back (until the next run); an
   * object removed after that stays out. */
  private removedShown = new Set<string>();

  /**
   * `objects` gives the scene's objects now; `rejected`, the boxes rejected before in this
   * browser (on any run: they stay rejected), and `remember` hears every change to them;
   * `removed`, the objects people deleted from the scene (stored with it, so no browser offers
   * them back).
   */
  constructor(
    private readonly objects: () => readonly SceneObject[],
    private rejected: readonly RejectedOffer[] = [],
    private readonly remember: (rejected: readonly RejectedOffer[]) => void = () => {},
    private readonly removed: () => readonly RejectedOffer[] = () => [],
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

  /** Offer the rejected boxes again (a rejection was a mistake), and removed objects' too. */
  forgetRejected(): void {
    this.rejected = [];
    this.removedShown = new Set(this.removed().map(removedKey));
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
    this.removedShown.clear();
    this.minScore = threshold;
    this.threshold = threshold;
    this.selected = this.open()[0]?.key ?? null;
  }

  reject(chosen: readonly Offer[]): void {
    this.rejected = [...this.rejected, ...chosen.map(({ cls, bbox }) => ({ cls, bbox }))];
    this.remember(this.rejected);
  }

  /** The boxes not offered: rejected here, or of objects people removed (unless asked for). */
  private leftOut(): readonly RejectedOffer[] {
    const removed = this.removed().filter((o) => !this.removedShown.has(removedKey(o)));
    return [...this.rejected, ...removed];
  }

  /**
   * The selection moves to the best open offer at the detector's threshold when its own is
   * gone (accepted or rejected); returns the open ones. Never to a fainter one: most of those
   * are wrong, and a second press of Accept would add it unchosen.
   */
  keepSelection(): Offer[] {
    const open = this.open();
    if (this.selected && !open.some((o) => o.key === this.selected)) {
      this.selected = open.find((o) => o.score >= this.threshold)?.key ?? null;
    }
    return open;
  }

  private openAbove(score: number, rejected = this.leftOut()): Offer[] {
    const offers = this.offers.filter((o) => o.score >= score);
    return openOffers(offers, this.objects(), rejected);
  }
}
