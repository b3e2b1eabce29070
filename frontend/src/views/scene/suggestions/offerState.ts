// The offers of one detector run: which are still open (not accepted, now objects; not
// rejected; not over an object of their class) and which one is selected. A run also keeps
// guesses, offered only when a person asks for them: the NYU-40 suggester's boxes, which name
// the classes COCO lacks, or without a suggester the detector's own boxes below its threshold
// (down to the class hints' score). Either finds about half again the real boxes the
// suggestions find, at the cost of many wrong ones (docs/detector.md, "In the browser").
import type { SceneObject } from "@holiscene/schema";
import type { DetectedBox } from "../../../inference/detectorTensor";
import { type Offer, offersOf, openOffers } from "../detectionOffers";
import type { RejectedOffer } from "./rejectedOffers";

const removedKey = ({ cls, bbox }: RejectedOffer) => JSON.stringify([cls, bbox]);

export class OfferState {
  /** This run's suggestions proper (at the detector's threshold), best first. */
  private offers: Offer[] = [];
  /** The detector's own boxes below its threshold: the guesses when there is no suggester. */
  private below: Offer[] = [];
  /** The guesses, best first; null while the suggester is still running. */
  private guessOffers: Offer[] | null = [];
  /** The guesses are shown (`showGuesses`). */
  private guessesShown = false;
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

  /** How many boxes the run offered (open or not), the guesses once shown. */
  get found(): number {
    return this.shownOffers().length;
  }

  /** The offers still open. */
  open(): Offer[] {
    return this.openOf(this.shownOffers());
  }

  /** The open suggestions proper ("Accept all" takes these: the guesses, once shown, are
   * mostly wrong and are accepted one by one). */
  confident(): Offer[] {
    return this.openOf(this.offers);
  }

  /** How many more offers would open if the guesses were shown (0 once they are, and while
   * the suggester is still running). */
  guesses(): number {
    if (this.guessesShown || this.guessOffers === null) return 0;
    return this.openOf([...this.offers, ...this.guessOffers]).length - this.open().length;
  }

  /** How many of the shown boxes are left out only because they were rejected before. */
  rejectedHidden(): number {
    return this.openOf(this.shownOffers(), []).length - this.open().length;
  }

  /** Offer the rejected boxes again (a rejection was a mistake), and removed objects' too. */
  forgetRejected(): void {
    this.rejected = [];
    this.removedShown = new Set(this.removed().map(removedKey));
    this.remember(this.rejected);
  }

  /** Offer the guesses as well; the selection stays where it was. */
  showGuesses(): void {
    this.guessesShown = true;
  }

  selectedOffer(): Offer | null {
    return this.open().find((o) => o.key === this.selected) ?? null;
  }

  /**
   * A new run's boxes (those at or above `threshold` are offered, the others down to the
   * faintest kept are the guesses unless `suggesterRunning`: then `setGuesses` brings them):
   * open unless rejected before, the best one selected.
   */
  reset(boxes: readonly DetectedBox[], threshold = 0, suggesterRunning = false): void {
    this.offers = offersOf(boxes.filter((b) => b.score >= threshold));
    this.below = offersOf(
      boxes.filter((b) => b.score < threshold),
      true,
    );
    this.guessOffers = suggesterRunning ? null : this.below;
    this.guessesShown = false;
    this.removedShown.clear();
    this.selected = this.open()[0]?.key ?? null;
  }

  /** The suggester's boxes as the guesses (null: there is none; the detector's own boxes
   * below its threshold are the guesses then). */
  setGuesses(boxes: readonly DetectedBox[] | null): void {
    this.guessOffers = boxes === null ? this.below : offersOf(boxes, true);
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
   * The selection moves to the best open suggestion when its own is gone (accepted or
   * rejected); returns the open offers. Never to a guess: most of those are wrong, and a
   * second press of Accept would add it unchosen.
   */
  keepSelection(): Offer[] {
    const open = this.open();
    if (this.selected && !open.some((o) => o.key === this.selected)) {
      this.selected = open.find((o) => !o.faint)?.key ?? null;
    }
    return open;
  }

  /** The suggestions, then the guesses once shown: a guess at the place of a suggestion is
   * the same thing, and the suggestion stands. */
  private shownOffers(): Offer[] {
    return this.guessesShown ? [...this.offers, ...(this.guessOffers ?? [])] : this.offers;
  }

  private openOf(offers: readonly Offer[], rejected = this.leftOut()): Offer[] {
    return openOffers(offers, this.objects(), rejected);
  }
}
