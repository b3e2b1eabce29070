// Object suggestions on the scene page: the object detector runs in this browser
// (inference/detector.ts, onnxruntime-web) on the scene's photo, by the "Detect objects" button
// or by itself when a scene without objects opens, and its boxes are offered as new objects:
// dashed boxes with class and score over the photo (boxes over an object of their class are
// left out). Click one to select it; Accept adds it to the scene (an add_object edit: the
// server makes its mask and answers with the new revision), Reject drops it for this visit.
// The bar above the photo says what the detector is doing, or why it failed.
import { api } from "../../api/client";
import { button, el, svgEl } from "../../dom";
import { activeDetector, detectorModel } from "../../inference/detector";
import { photoPixels } from "../../inference/supportSuggestions";
import { registerShortcut } from "../../shortcuts";
import type { ObjectEditor } from "../../state/objectEditor";
import { plural, type SceneSession } from "../../state/sceneSession";
import { isStructural } from "../../state/supportGraph";
import { frameFor, strokeWidth } from "../photo/arrowGeometry";
import { addObjectEdit, type Offer, offerLabel, offersOf, openOffers } from "./detectionOffers";
import "./objectSuggestions.css";

const SCOPE = "Object suggestions";
export const DETECT_KEY = "D";
export const ACCEPT_KEY = "Y";
export const ACCEPT_ALL_KEY = "Shift+Y";
export const REJECT_KEY = "X";

type Busy = "loading" | "detecting" | "adding" | null;

const MB = (bytes: number) => `${(bytes / 1e6).toFixed(1)} MB`;
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
  const frame = frameFor(width, height);
  const layer = svgEl("g", { class: "detector-layer", "data-testid": "detector-layer" });
  svg.append(layer);

  let offers: Offer[] = []; // this run's boxes, best first
  let rejected: Offer[] = [];
  let selected: string | null = null;
  let busy: Busy = null;
  let status = "";
  let failed = false;
  let disposed = false;

  const detectButton = button("Detect objects", {
    testid: "detect-objects",
    title: `Find objects in the photo with the object detector, in this browser (${DETECT_KEY})`,
  });
  const statusLine = el("span", {
    className: "detector-status",
    testid: "detector-status",
    attrs: { role: "status" },
  });
  const action = (text: string, testid: string, title: string, primary = false) =>
    button(text, { className: primary ? "primary" : "", testid, title });
  const acceptButton = action(
    "Accept",
    "accept-suggestion",
    `Add the selected box as an object (${ACCEPT_KEY})`,
    true,
  );
  const rejectButton = action(
    "Reject",
    "reject-suggestion",
    `Drop the selected box (${REJECT_KEY})`,
  );
  const acceptAllButton = action(
    "Accept all",
    "accept-all-suggestions",
    `Add every box shown as an object (${ACCEPT_ALL_KEY})`,
  );
  const rejectAllButton = action("Reject all", "reject-all-suggestions", "Drop every box shown");
  const selection = el("span", { className: "detector-selection", testid: "detector-selection" });
  const actions = el(
    "span",
    { className: "detector-actions", testid: "detector-actions" },
    selection,
    acceptButton,
    rejectButton,
    acceptAllButton,
    rejectAllButton,
  );
  const bar = el(
    "div",
    { className: "detector-bar", testid: "detector-bar" },
    detectButton,
    statusLine,
    actions,
  );
  photoBody.insertBefore(bar, photoBody.querySelector(".photo-box"));

  /** The offers still open: not accepted (now objects), rejected, or over an object. */
  const shown = () => openOffers(offers, session.objects, rejected);
  const selectedOffer = () => shown().find((o) => o.key === selected) ?? null;

  const draw = () => {
    const open = shown();
    if (selected && !open.some((o) => o.key === selected)) selected = open[0]?.key ?? null;
    const stroke = strokeWidth(frame);
    const size = stroke * 5;
    // Larger boxes first, so a smaller box inside one stays clickable on top.
    const byArea = [...open].sort(
      (a, b) =>
        (b.bbox[2] - b.bbox[0]) * (b.bbox[3] - b.bbox[1]) -
        (a.bbox[2] - a.bbox[0]) * (a.bbox[3] - a.bbox[1]),
    );
    layer.replaceChildren(
      ...byArea.map((offer) => {
        const [x1, y1, x2, y2] = offer.bbox;
        const label = offerLabel(offer);
        const labelWidth = label.length * size * 0.62 + size * 0.6;
        const labelHeight = size * 1.35;
        // Above the box, in the frame's margin if need be; inside it at the photo's top.
        const top = y1 - labelHeight >= -frame.margin ? y1 - labelHeight : y1;
        const left = Math.min(x1, width + frame.margin - labelWidth);
        const isSelected = offer.key === selected;
        const group = svgEl(
          "g",
          {
            class: `detector-suggestion${isSelected ? " is-selected" : ""}`,
            "data-testid": "detector-suggestion",
            "data-key": offer.key,
            "data-class": offer.cls,
          },
          svgEl(
            "title",
            {},
            `Suggested ${label} (the detector's ${offer.sourceClass}): click to select`,
          ),
          svgEl("rect", {
            class: "detector-box-halo",
            x: x1,
            y: y1,
            width: x2 - x1,
            height: y2 - y1,
            "stroke-width": stroke * (isSelected ? 2.2 : 1.6),
          }),
          svgEl("rect", {
            class: "detector-box",
            x: x1,
            y: y1,
            width: x2 - x1,
            height: y2 - y1,
            "stroke-width": stroke * (isSelected ? 1.4 : 0.9),
            "stroke-dasharray": `${stroke * 4} ${stroke * 2.5}`,
          }),
          svgEl("rect", {
            class: "detector-label-box",
            x: left,
            y: top,
            width: labelWidth,
            height: labelHeight,
            rx: size * 0.25,
          }),
          svgEl(
            "text",
            {
              class: "detector-label",
              x: left + size * 0.3,
              y: top + labelHeight / 2,
              dy: "0.35em",
              "font-size": size,
            },
            label,
          ),
        );
        return group;
      }),
    );
    // The bar: what is going on, and the actions while there is something to act on.
    const editable = session.editable;
    detectButton.disabled = busy !== null;
    statusLine.textContent = status;
    statusLine.classList.toggle("alert", failed);
    statusLine.classList.toggle("alert--error", failed);
    statusLine.setAttribute("role", failed ? "alert" : "status");
    actions.hidden = open.length === 0;
    const chosen = selectedOffer();
    selection.textContent = chosen ? `Selected: ${offerLabel(chosen)}` : "No box selected";
    const why = editable ? "" : " (the scene is read only)";
    acceptButton.disabled = busy !== null || !editable || selectedOffer() === null;
    acceptAllButton.disabled = busy !== null || !editable;
    rejectButton.disabled = busy !== null || selectedOffer() === null;
    rejectAllButton.disabled = busy !== null;
    acceptButton.title = `Add the selected box as an object (${ACCEPT_KEY})${why}`;
    acceptAllButton.title = `Add every box shown as an object (${ACCEPT_ALL_KEY})${why}`;
  };

  const say = (text: string, error = false) => {
    status = text;
    failed = error;
    draw();
  };

  /** What the run found, for the status line (`loadMs`: loading the detector, if it was). */
  const foundText = (loadMs: number, runMs: number) => {
    const open = shown().length;
    const seconds = (ms: number) => `${(ms / 1000).toFixed(1)} s`;
    const time =
      `in ${seconds(runMs)}` +
      (loadMs > 100 ? ` (loading the detector took ${seconds(loadMs)})` : "");
    if (offers.length === 0) return `No objects found ${time}.`;
    if (open === 0) return `${plural(offers.length, "box")} found ${time}, all labelled already.`;
    return `${plural(open, "object")} suggested ${time}: click a box, then Accept or Reject.`;
  };

  const detect = async () => {
    if (busy !== null) return;
    busy = "loading";
    say("Loading the object detector…");
    const start = performance.now();
    try {
      const info = await activeDetector();
      const model = await detectorModel(info, (loaded, total) => {
        if (busy === "loading")
          say(`Loading the object detector… ${MB(loaded)} of ${MB(total ?? info.model_bytes)}`);
      });
      const loaded = performance.now();
      busy = "detecting";
      say("Detecting objects…");
      const pixels = await photoPixels(api.imageUrl(session.sceneId));
      const result = await model.detect(pixels);
      if (disposed) return;
      offers = offersOf(result.boxes);
      rejected = [];
      selected = shown()[0]?.key ?? null;
      busy = null;
      say(foundText(loaded - start, performance.now() - loaded));
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
    say(
      chosen.length === 1
        ? `Adding ${offerLabel(chosen[0] as Offer)}…`
        : `Adding ${plural(chosen.length, "object")}…`,
    );
    // One undoable action; after a conflict the editor re-sends it on the latest revision.
    const ids = objectEditor.newObjectIds(chosen.length);
    const edits = chosen.map((offer, i) => addObjectEdit(offer, ids[i] as string));
    const names = edits.map((e) => `${e.id} (${e.class})`).join(", ");
    const saved = await objectEditor.apply(edits, `add ${names}`);
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

  const reject = (chosen: Offer[]) => {
    if (busy !== null || chosen.length === 0) return;
    rejected = [...rejected, ...chosen];
    const left = shown().length;
    const what =
      chosen.length === 1 ? offerLabel(chosen[0] as Offer) : plural(chosen.length, "suggestion");
    say(`Rejected ${what}.${left > 0 ? ` ${plural(left, "suggestion")} left.` : ""}`);
  };

  const onSelected = (act: (offer: Offer) => void) => () => {
    const offer = selectedOffer();
    if (offer) act(offer);
    else say("Click a suggested box first.");
  };

  detectButton.addEventListener("click", () => void detect());
  acceptButton.addEventListener(
    "click",
    onSelected((o) => void accept([o])),
  );
  rejectButton.addEventListener(
    "click",
    onSelected((o) => reject([o])),
  );
  acceptAllButton.addEventListener("click", () => void accept(shown()));
  rejectAllButton.addEventListener("click", () => reject(shown()));
  // A click on a box selects it, and is not a click on the photo (arrow editing).
  const pick = (event: Event) => {
    const group = (event.target as Element).closest<SVGGElement>(".detector-suggestion");
    if (!group) return;
    event.stopPropagation();
    if (event.type === "click") {
      selected = group.dataset.key ?? null;
      draw();
    }
  };
  layer.addEventListener("click", pick);
  layer.addEventListener("pointerdown", pick);

  const hasOffers = () => shown().length > 0;
  const removeKeys = [
    registerShortcut({
      keys: DETECT_KEY,
      description: "Detect objects in the photo (suggested boxes to accept or reject)",
      scope: SCOPE,
      run: () => void detect(),
      enabled: () => busy === null,
    }),
    registerShortcut({
      keys: ACCEPT_KEY,
      description: "Accept the selected suggested box as an object",
      scope: SCOPE,
      run: onSelected((o) => void accept([o])),
      enabled: () => hasOffers() && busy === null && session.editable,
    }),
    registerShortcut({
      keys: ACCEPT_ALL_KEY,
      description: "Accept every suggested box as an object",
      scope: SCOPE,
      run: () => void accept(shown()),
      enabled: () => hasOffers() && busy === null && session.editable,
    }),
    registerShortcut({
      keys: REJECT_KEY,
      description: "Reject the selected suggested box",
      scope: SCOPE,
      run: onSelected((o) => reject([o])),
      enabled: () => hasOffers() && busy === null,
    }),
  ];

  const unsubscribe = session.subscribe((change) => {
    if (change === "document" || change === "lock") draw();
  });
  draw();
  // A scene without objects: look for some at once (unless it cannot be edited).
  const objects = session.objects.filter((o) => !isStructural(o.class));
  if (objects.length === 0 && session.editable) void detect();

  return () => {
    disposed = true;
    unsubscribe();
    for (const remove of removeKeys) remove();
    layer.remove();
    bar.remove();
  };
}
