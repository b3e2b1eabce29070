// The bar above the photo for object suggestions: "Detect objects", what the detector is doing
// (or why it failed) with "Show N guesses" after it when the run has guesses to offer (the
// suggester's boxes: offerState.ts) and "Offer N rejected again" when boxes rejected before
// are left out,
// and while there are boxes: the selected one, Accept, Reject, Accept all, Reject all.
import { button, el } from "../../../dom";
import { plural } from "../../../state/sceneSession";
import { type Offer, offerLabel } from "../detectionOffers";

export const DETECT_KEY = "D";
export const ACCEPT_KEY = "Y";
export const ACCEPT_ALL_KEY = "Shift+Y";
export const REJECT_KEY = "X";

/** "3 guesses" */
export const guessesText = (guesses: number) => plural(guesses, "guess");

export interface DetectorBarState {
  /** The detector is loading or running, or objects are being added. */
  busy: boolean;
  status: string;
  failed: boolean;
  editable: boolean;
  /** How many boxes are open. */
  open: number;
  /** How many of them are suggestions proper, not guesses ("Accept all" takes those). */
  confident: number;
  /** How many guesses the run has that are not shown yet. */
  guesses: number;
  /** How many of the run's boxes are left out because they were rejected before. */
  rejected: number;
  chosen: Offer | null;
}

export interface DetectorBarActions {
  detect(): void;
  acceptSelected(): void;
  rejectSelected(): void;
  acceptAll(): void;
  rejectAll(): void;
  showGuesses(): void;
  offerRejected(): void;
}

export interface DetectorBar {
  element: HTMLElement;
  show(state: DetectorBarState): void;
}

export function detectorBar(actions: DetectorBarActions): DetectorBar {
  const detectTitle = `Find objects in the photo with the object detector, in this browser (${DETECT_KEY})`;
  const detectButton = button("Detect objects", {
    testid: "detect-objects",
    title: detectTitle,
    onClick: actions.detect,
  });
  const statusLine = el("span", {
    className: "detector-status",
    testid: "detector-status",
    attrs: { role: "status" },
  });
  const action = (
    text: string,
    testid: string,
    title: string,
    onClick: () => void,
    primary = false,
  ) => button(text, { className: primary ? "primary" : "", testid, title, onClick });
  const acceptButton = action(
    "Accept",
    "accept-suggestion",
    `Add the selected box as an object (${ACCEPT_KEY})`,
    actions.acceptSelected,
    true,
  );
  const rejectButton = action(
    "Reject",
    "reject-suggestion",
    `Drop the selected box (${REJECT_KEY})`,
    actions.rejectSelected,
  );
  const acceptAllButton = action(
    "Accept all",
    "accept-all-suggestions",
    `Add every suggested box as an object (${ACCEPT_ALL_KEY})`,
    actions.acceptAll,
  );
  const rejectAllButton = action(
    "Reject all",
    "reject-all-suggestions",
    "Drop every box shown",
    actions.rejectAll,
  );
  // A link-sized button at the end of the status line: the line's height stays the same
  // whether it shows or not, so the photo does not move when a detection ends.
  const guessesButton = button("Show guesses", {
    className: "link-like detector-more",
    testid: "show-guess-suggestions",
    title:
      "Also offer guesses, drawn pale: boxes named with the indoor classes COCO lacks (lamp, " +
      "pillow, picture, night stand...) by a detector trained on synthetic rooms. More of the " +
      "real objects, and many wrong boxes",
    onClick: actions.showGuesses,
  });
  const rejectedButton = button("Offer rejected again", {
    className: "link-like detector-more",
    testid: "offer-rejected-suggestions",
    title:
      "Offer again the boxes rejected on this scene (rejections are remembered in this browser) " +
      "and the boxes of objects people removed from it",
    onClick: actions.offerRejected,
  });
  const selection = el("span", { className: "detector-selection", testid: "detector-selection" });
  const actionRow = el(
    "span",
    { className: "detector-actions", testid: "detector-actions" },
    selection,
    acceptButton,
    rejectButton,
    acceptAllButton,
    rejectAllButton,
  );
  // One line until the first detection: the button with the status beside it, one line (its
  // whole text in its title) unless it reports a failure; the photo's tool row has no room for
  // the button (the zoom controls appear there). From then on the actions keep a line of their
  // own below, even with nothing to act on, so the photo does not move under the pointer when
  // a detection ends.
  const element = el(
    "div",
    { className: "detector-bar", testid: "detector-bar" },
    detectButton,
    el("div", { className: "detector-status-row" }, statusLine, guessesButton, rejectedButton),
    actionRow,
  );
  // Until the first detection, nothing can appear there: no room is kept (a band of blank
  // space above the photo otherwise).
  let used = false;
  return {
    element,
    show({ busy, status, failed, editable, open, confident, guesses, rejected, chosen }) {
      used ||= busy || open > 0;
      actionRow.classList.toggle("is-unused", !used);
      detectButton.disabled = busy;
      // A reviewer may look at what the detector finds; adding it is the annotator's.
      detectButton.title = editable
        ? detectTitle
        : `${detectTitle}: to look at only, the scene is read only`;
      guessesButton.hidden = guesses === 0;
      guessesButton.disabled = busy;
      guessesButton.textContent = `Show ${guessesText(guesses)}`;
      rejectedButton.hidden = rejected === 0;
      rejectedButton.disabled = busy;
      rejectedButton.textContent = `Offer ${rejected} rejected again`;
      statusLine.textContent = status;
      statusLine.title = status;
      statusLine.classList.toggle("alert", failed);
      statusLine.classList.toggle("alert--error", failed);
      statusLine.setAttribute("role", failed ? "alert" : "status");
      actionRow.hidden = open === 0;
      // While boxes are open the bar stays in view under the photo's tools: Accept and Reject
      // are at hand while working low on a tall photo.
      element.classList.toggle("is-offering", open > 0);
      const picked = chosen ? `Selected: ${offerLabel(chosen)}` : "No box selected";
      // Looking at the detector's boxes is fine on a read-only scene; adding them is not.
      selection.textContent = editable ? picked : `${picked} · view only: the scene is read only`;
      selection.title = selection.textContent;
      const why = editable ? "" : " (the scene is read only)";
      acceptButton.disabled = busy || !editable || chosen === null;
      acceptAllButton.disabled = busy || !editable || confident === 0;
      // With guesses shown, "all" would read as every box: say which ones it takes.
      acceptAllButton.textContent =
        open > confident && confident > 0
          ? `Accept the ${plural(confident, "suggestion")}`
          : "Accept all";
      // Rejections are remembered for the scene (in this browser): also the editor's to make.
      rejectButton.disabled = busy || !editable || chosen === null;
      rejectAllButton.disabled = busy || !editable;
      acceptButton.title = `Add the selected box as an object (${ACCEPT_KEY})${why}`;
      acceptAllButton.title = `Add every suggested box as an object (${ACCEPT_ALL_KEY}); guesses one by one${why}`;
    },
  };
}
