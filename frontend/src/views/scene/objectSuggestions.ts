// Object suggestions on the scene page: the object detector runs in this browser
// (inference/detector.ts, onnxruntime-web) on the scene's photo, by the "Detect objects" button
// or by itself when a scene without objects opens, and its boxes are offered as new objects:
// dashed boxes with class and score over the photo (boxes over an object of their class are
// left out). Click one to select it; Accept adds it to the scene (an add_object edit: the
// server makes its mask and answers with the new revision), Reject drops it: later runs leave
// it out too (remembered in this browser, suggestions/rejectedOffers.ts) until the person asks
// for the rejected boxes again. On request ("Show N guesses") it also offers the suggester's
// boxes, which name the indoor classes COCO lacks (or, without a suggester, the detector's own
// below its threshold).
// The bar above the photo says what the detector is doing, or why it failed.
import { SCORE_THRESHOLD } from "../../inference/detectorTensor";
import type { ObjectEditor } from "../../state/objectEditor";
import { plural, type SceneSession } from "../../state/sceneSession";
import { isStructural } from "../../state/supportGraph";
import { frameFor } from "../photo/arrowGeometry";
import { classHints } from "./classHints";
import { type Offer, offerLabel } from "./detectionOffers";
import { addingText, addOffers } from "./suggestions/addOffers";
import { type DetectorBarActions, detectorBar, guessesText } from "./suggestions/detectorBar";
import { type DetectorRun, foundText, runDetector, runSuggester } from "./suggestions/detectorRun";
import { offerBoxes } from "./suggestions/offerBoxes";
import { OfferState } from "./suggestions/offerState";
import { loadRejected, saveRejected } from "./suggestions/rejectedOffers";
import { suggestionKeys } from "./suggestions/suggestionKeys";
import "./objectSuggestions.css";

// Its parts, in suggestions/: the bar (detectorBar), a detector run (detectorRun), the boxes on
// the photo (offerBoxes) and the keys; this module keeps the offers and accepts or rejects them.
export { ACCEPT_ALL_KEY, ACCEPT_KEY, DETECT_KEY, REJECT_KEY } from "./suggestions/detectorBar";

type Busy = "loading" | "detecting" | "adding" | null;

const message = (error: unknown) => (error instanceof Error ? error.message : String(error));

/**
 * The bar (inserted at the top of `photoBody`, above the photo) and the layer of dashed boxes
 * (in the photo's SVG, which mountPhotoView made). Returns the function that removes them.
 */
export function mountObjectSuggestions(
  photoBody: HTMLElement,
  session: SceneSession,
  objectEditor: ObjectEditor,
): () => void {
  const svg = photoBody.querySelector<SVGSVGElement>("svg.photo-svg");
  if (!svg) throw new Error("mount the photo view before the object suggestions");
  const { width, height } = session.doc.scene.image;

  const state = new OfferState(
    () => session.objects,
    loadRejected(session.sceneId),
    (rejected) => saveRejected(session.sceneId, rejected),
    () => (session.doc.scene.removed_by_person ?? []).map((o) => ({ cls: o.class, bbox: o.bbox })),
  );
  let busy: Busy = null;
  let status = "";
  let failed = false;
  let disposed = false;

  const shown = () => state.open();
  const onSelected = (act: (offer: Offer) => void) => () => {
    const offer = state.selectedOffer();
    if (offer) act(offer);
    else say("Click a suggested box first.");
  };
  const actions: DetectorBarActions = {
    detect: () => void detect(),
    acceptSelected: onSelected((o) => void accept([o])),
    rejectSelected: onSelected((o) => reject([o])),
    acceptAll: () => {
      const confident = state.confident();
      if (confident.length > 0) void accept(confident);
      else
        say("Accept all takes the suggestions, not the guesses: select a guess and press Accept.");
    },
    rejectAll: () => reject(shown()),
    showGuesses: () => showGuesses(),
    offerRejected: () => offerRejected(),
  };

  const boxes = offerBoxes(svg, frameFor(width, height), width, (key) => {
    state.selected = key;
    draw();
  });
  const bar = detectorBar(actions);
  photoBody.insertBefore(bar.element, photoBody.querySelector(".photo-box"));

  const draw = () => {
    const open = state.keepSelection();
    boxes.draw(open, state.selected);
    bar.show({
      busy: busy !== null,
      status,
      failed,
      editable: session.editable,
      open: open.length,
      confident: state.confident().length,
      guesses: state.guesses(),
      rejected: state.rejectedHidden(),
      chosen: state.selectedOffer(),
    });
  };

  // What the last run found, said again when the scene changes under it (an object deleted
  // makes its box a rejected one), unless something else has been said since.
  let lastRun: DetectorRun | null = null;
  let showingFound = false;
  const say = (text: string, error = false) => {
    status = text;
    failed = error;
    showingFound = false;
    draw();
  };
  const sayFound = () => {
    if (!lastRun) return;
    say(foundText(state.found, shown().length, lastRun, state.rejectedHidden()));
    showingFound = true;
  };

  const detect = async () => {
    if (busy !== null) return;
    busy = "loading";
    say("Loading the object detector…");
    try {
      const run = await runDetector(session.sceneId, say, () => {
        busy = "detecting";
        say("Detecting objects…");
      });
      if (disposed) return;
      state.reset(run.seen, SCORE_THRESHOLD, true);
      classHints.set(session.sceneId, run.seen);
      busy = null;
      lastRun = run;
      sayFound();
      void guess(run);
    } catch (error) {
      if (disposed) return;
      busy = null;
      say(`Could not detect objects: ${message(error)}`, true);
    }
  };

  /** Add offers as objects: one request; the new revision comes back with their masks. */
  const accept = async (chosen: Offer[]) => {
    if (busy !== null || chosen.length === 0) return;
    if (!session.editable) {
      say("The scene is read only: nothing can be added now.", true);
      return;
    }
    busy = "adding";
    say(addingText(chosen));
    const { saved, names } = await addOffers(objectEditor, chosen);
    if (disposed) return;
    busy = null;
    if (!saved) {
      const why = objectEditor.failure?.message ?? "not saved";
      say(`Could not add the object${chosen.length === 1 ? "" : "s"}: ${why}`, true);
      return;
    }
    const left = shown().length;
    say(`Added ${names}.${left > 0 ? ` ${plural(left, "suggestion")} left.` : ""}`);
  };

  /** The suggester runs after the suggestions are up (they need not wait for it); "Show N
   * guesses" appears when it is done. Without it the suggestions still stand. */
  const guess = async (run: DetectorRun) => {
    try {
      const boxes = await runSuggester(run);
      if (disposed || lastRun !== run) return; // another run began meanwhile
      state.setGuesses(boxes);
      if (boxes) classHints.add(session.sceneId, boxes);
      draw();
    } catch (error) {
      if (disposed || lastRun !== run) return;
      state.setGuesses(null);
      say(
        `Could not run the suggester (the detector's own fainter boxes are the guesses): ${message(error)}`,
        true,
      );
    }
  };

  /** Offer the guesses too: more real objects, and more wrong boxes. */
  const showGuesses = () => {
    const guesses = state.guesses();
    if (busy !== null || guesses === 0) return;
    state.showGuesses();
    say(
      `Showing ${guessesText(guesses)} as well (pale): most of them are wrong; accept the right ones one by one.`,
    );
  };

  /** Offer again the boxes rejected on this scene, in this run and before. */
  const offerRejected = () => {
    const hidden = state.rejectedHidden();
    if (busy !== null || hidden === 0) return;
    state.forgetRejected();
    say(`Offering ${plural(hidden, "rejected box")} again.`);
  };

  const reject = (chosen: Offer[]) => {
    if (busy !== null || chosen.length === 0) return;
    state.reject(chosen);
    const left = shown().length;
    const what =
      chosen.length === 1 ? offerLabel(chosen[0] as Offer) : plural(chosen.length, "suggestion");
    say(`Rejected ${what}.${left > 0 ? ` ${plural(left, "suggestion")} left.` : ""}`);
  };

  const removeKeys = suggestionKeys({
    ...actions,
    idle: () => busy === null,
    hasOffers: () => shown().length > 0,
    editable: () => session.editable,
  });

  const unsubscribe = session.subscribe((change) => {
    if (change === "document" && showingFound && busy === null) sayFound();
    else if (change === "document" || change === "lock") draw();
  });
  draw();
  // A scene without objects: look for some at once (unless it cannot be edited).
  const objects = session.objects.filter((o) => !isStructural(o.class));
  if (objects.length === 0 && session.editable) void detect();

  return () => {
    disposed = true;
    unsubscribe();
    removeKeys();
    boxes.layer.remove();
    bar.element.remove();
  };
}
