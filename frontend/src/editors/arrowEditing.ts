// Editing supports with the mouse on the photo. Click an arrow (or an unsupported object's
// "?" flag) to select its object and arm a pick: the next click on another object makes that
// object the supporter (inside its mask, off its own drawn arrow). S arms a pick for an object
// selected otherwise (its label, the list, N). Or drag an arrow (from its head or anywhere on
// it) and drop it on the new supporter.
// Clicking an object only selects it unless a pick is armed: an annotator who clicks from
// object to object to look at them changes nothing. An arrow runs over its own object to the
// object's centre, so there only the drawn arrow away from that centre arms a pick; its head
// there and the wider margin around it that makes arrows easy to hit elsewhere belong to the
// object (a click there selects it, or picks it while a pick is armed). While a pick is
// armed, a click on another drawn arrow takes up that arrow instead, and the object under the
// pointer shows the arrow it would get (a dashed line).
// Clicking the selected object or the background clears the selection. While the scene is
// read only, clicks only select.
import { svgEl } from "../dom";
import { type RoomSurface, roomSurfaceAt } from "../geometry/roomSurface";
import { registerShortcut } from "../shortcuts";
import type { SceneSession } from "../state/sceneSession";
import { setSupporter } from "./supportActions";

export const PICK_SUPPORTER_KEY = "S";

export interface PhotoPicking {
  svg: SVGSVGElement;
  /** The object whose mask (or box) is under the pointer, arrows aside. */
  objectAt(event: MouseEvent): string | null;
  /** The pointer in image pixels. */
  toImage(event: MouseEvent): [number, number] | null;
  /** Where an object's arrows end (its centroid), in image pixels. */
  centroid(id: string): [number, number] | null;
  bbox(id: string): readonly [number, number, number, number] | null;
  strokeWidth(): number;
}

const DRAG_PX = 6; // screen pixels before a press on an arrow becomes a drag
const DROP_HINT_MS = 3000; // how long the hint at a drop on no object stays

const arrowAt = (event: Event): string | null =>
  (event.target as Element | null)?.closest<SVGGElement>(".arrow[data-child]")?.dataset.child ??
  null;

/** The press (`at`, in image pixels) is on the arrow's invisible hit margin, off the arrow
 * drawn (its white halo; the head takes its own presses). */
function onHitMargin(event: Event, at: readonly [number, number] | null): boolean {
  const target = event.target as Element | null;
  if (!at || !target?.classList.contains("arrow-hit")) return false;
  const halo = target.closest(".arrow")?.querySelector<SVGGeometryElement>(".arrow-halo");
  // Without the geometry (an old browser) the whole margin stays the arrow's.
  if (typeof halo?.isPointInStroke !== "function") return false;
  return !halo.isPointInStroke(new DOMPoint(at[0], at[1]));
}

/** How far from its head (its object's centre) a click on an arrow is a click on the object:
 * in stroke widths (about 17 screen pixels), and at most this share of the arrow's length (so
 * that on a short arrow its shaft still takes it up). */
const HEAD_STROKES = 6;
const HEAD_SHARE = 0.5;
/** How near the centre of the object under it (about 8 screen pixels) a click on another
 * object's arrow is a click on that object. */
const CENTRE_STROKES = 3;

/** The object whose "?" flag (no supporter) is under the pointer. */
const flagAt = (event: Event): string | null =>
  (event.target as Element | null)?.closest<SVGGElement>("[data-unsupported]")?.dataset
    .unsupported ?? null;

export function mountArrowEditing(picking: PhotoPicking, session: SceneSession): () => void {
  const { svg } = picking;
  const dragLayer = svgEl("g", { class: "drag-layer", "data-testid": "drag-layer" });
  svg.append(dragLayer);
  let press: { child: string; x: number; y: number; dragging: boolean } | null = null;
  let swallowClick = false;
  // The pick lives in the session (the selection bar's hint says what a click will do).
  const arm = (child: string | null) =>
    session.setPicking(child !== null && session.editable ? child : null);

  const pickSupporter = (child: string, parent: string) => {
    const current = session.displayed(child);
    // Picking the supporter it has is no edit: a click meant to look at that object must
    // not turn the pipeline's guess into a person's label (A confirms a guess on purpose).
    // The model's live suggestion is not stored yet (the list still shows the old
    // supporter): picking it is the person's answer, as A would be.
    session.say(
      current?.parent === parent && !current.suggested
        ? `${child} is on ${parent} already${current.support?.source === "auto" ? ": A accepts that guess" : ""}.`
        : setSupporter(session, child, parent),
    );
    arm(null); // picked: the next click selects again
  };

  /** The floor, wall or ceiling the photo shows under the pointer (by the stored room and
   * camera), where there is no object: a drop there picks it. (Not a click while a pick is
   * armed: a click on an arrow arms one, and a click on the floor to deselect would then
   * change the label.) */
  const surfaceAt = (event: MouseEvent): RoomSurface | null => {
    const at = picking.toImage(event);
    const { camera, layout, image } = session.doc.scene;
    const onPhoto = at && at[0] >= 0 && at[1] >= 0 && at[0] < image.width && at[1] < image.height;
    return onPhoto ? roomSurfaceAt(at, camera, layout?.corners_3d) : null;
  };

  /** The press is on the arrow of `child` near its head, the centre of the object: where
   * people click to select the object (on a small object the arrow covers much of it). */
  /** How far the press is from `id`'s centre, where its arrows end (image pixels; infinite
   * when either is unknown). */
  const fromCentre = (event: MouseEvent, id: string): number => {
    const at = picking.toImage(event);
    const centre = picking.centroid(id);
    return at && centre ? Math.hypot(at[0] - centre[0], at[1] - centre[1]) : Infinity;
  };

  const nearOwnHead = (event: MouseEvent, child: string): boolean => {
    const head = picking.centroid(child);
    if (!head) return false;
    const shaft = (event.target as Element | null)
      ?.closest(".arrow")
      ?.querySelector<SVGGeometryElement>(".arrow-shaft");
    let length = Number.POSITIVE_INFINITY;
    if (typeof shaft?.getTotalLength === "function") {
      // The shaft ends where the head's triangle begins: the head's length is added.
      const shaftLength = shaft.getTotalLength();
      const end = shaft.getPointAtLength(shaftLength);
      length = shaftLength + Math.hypot(end.x - head[0], end.y - head[1]);
    }
    const reach = Math.min(HEAD_STROKES * picking.strokeWidth(), HEAD_SHARE * length);
    return fromCentre(event, child) <= reach;
  };

  /** The press is within a few pixels of `id`'s centre. */
  const nearCentre = (event: MouseEvent, id: string): boolean =>
    fromCentre(event, id) <= CENTRE_STROKES * picking.strokeWidth();

  const onClick = (event: MouseEvent) => {
    if (swallowClick) {
      swallowClick = false;
      return;
    }
    const drawn = arrowAt(event);
    const arrow = drawn ?? flagAt(event);
    const under = picking.objectAt(event);
    // A click at an object's centre is about that object: its own arrow's head is there (its
    // mask may not be, a chair's), and another arrow's shaft may pass over it.
    const centred =
      drawn === null
        ? null
        : nearOwnHead(event, drawn)
          ? drawn
          : under !== null && under !== drawn && nearCentre(event, under)
            ? under
            : null;
    const object = centred ?? under;
    const selected = session.selected;
    const armed = session.picking !== null && session.picking === selected;
    // The margin of an arrow over its own object is the object's, and so is an object's
    // centre; the rest of the arrow drawn (or a "?" flag) is the arrow's, armed pick or not:
    // a person looking from arrow to arrow takes up each in turn and changes nothing.
    const onArrow =
      arrow !== null &&
      centred === null &&
      !(arrow === object && onHitMargin(event, picking.toImage(event)));
    if (armed && object && object !== selected && !onArrow) {
      pickSupporter(selected, object);
      return;
    }
    if (arrow && !onArrow) {
      session.say(null);
      session.select(object);
      arm(null);
      return;
    }
    if (arrow) {
      session.say(null);
      session.select(arrow);
      arm(arrow);
      return;
    }
    session.say(null);
    session.select(object === selected ? null : object);
    arm(null);
  };

  /** The arrow `child` would get from where the pointer is: a dashed line to the pointer and
   * the box of the object under it (the one a drop or a click would make its supporter), or,
   * while `dragging`, the name of the room's surface a drop there would pick (a click there
   * picks none). */
  const drawPick = (child: string, event: MouseEvent, dragging: boolean) => {
    const to = picking.centroid(child);
    const at = picking.toImage(event);
    const target = picking.objectAt(event);
    const box = target && target !== child ? picking.bbox(target) : null;
    // Between objects, the room's surface a drop would pick is named at the pointer.
    const surface = dragging && target === null ? surfaceAt(event) : null;
    const width = picking.strokeWidth();
    dragLayer.replaceChildren(
      ...(surface && at
        ? [
            svgEl(
              "text",
              {
                class: "drop-hint",
                "data-testid": "drop-surface",
                x: at[0] + width * 3,
                y: at[1] - width * 3,
                "font-size": width * 5,
                "stroke-width": width * 1.2,
              },
              surface,
            ),
          ]
        : []),
      ...(box
        ? [
            svgEl("rect", {
              class: "drop-target",
              x: box[0],
              y: box[1],
              width: box[2] - box[0],
              height: box[3] - box[1],
              "stroke-width": width,
            }),
          ]
        : []),
      ...(to && at
        ? [
            svgEl("path", {
              class: "drag-line",
              "data-testid": "drag-line",
              d: `M ${at[0].toFixed(1)} ${at[1].toFixed(1)} L ${to[0].toFixed(1)} ${to[1].toFixed(1)}`,
              "stroke-width": width * 1.5,
              "stroke-dasharray": `${width * 3} ${width * 2}`,
            }),
          ]
        : []),
    );
  };

  const onMove = (event: PointerEvent) => {
    if (!press) return;
    if (!press.dragging && Math.hypot(event.clientX - press.x, event.clientY - press.y) < DRAG_PX)
      return;
    press.dragging = true;
    svg.classList.add("is-picking");
    drawPick(press.child, event, true);
  };
  // An armed pick shows what a click would do before it is made.
  const armedChild = () =>
    session.picking !== null && session.picking === session.selected ? session.picking : null;
  const onHover = (event: MouseEvent) => {
    if (press) return;
    const child = armedChild();
    if (child) drawPick(child, event, false);
  };
  const clearPreview = () => {
    if (!press) dragLayer.replaceChildren();
  };
  const onUp = (event: PointerEvent) => {
    window.removeEventListener("pointermove", onMove);
    window.removeEventListener("pointerup", onUp);
    const done = press;
    press = null;
    svg.classList.remove("is-picking");
    dragLayer.replaceChildren();
    if (!done?.dragging) return;
    swallowClick = true; // the click that ends a drag is not a pick
    setTimeout(() => {
      swallowClick = false;
    }, 0);
    const target = picking.objectAt(event) ?? surfaceAt(event);
    session.select(done.child);
    if (target && target !== done.child) pickSupporter(done.child, target);
    // Outside the room's faces (the margin beyond the photo, or no room known): say how to
    // choose them, in the line under the photo and where the pointer is (that line may be
    // below the window).
    else if (!target) {
      session.say(
        `Dropped on no object: ${done.child} keeps its supporter. For the floor, a wall or ` +
          "the ceiling press F, W or C (it stays selected).",
      );
      const at = picking.toImage(event);
      if (at) showDropHint(at);
    }
  };

  let hintTimer = 0;
  const showDropHint = ([x, y]: readonly [number, number]) => {
    const width = picking.strokeWidth();
    const box = svg.viewBox.baseVal;
    const right = x > box.x + box.width / 2;
    const low = y > box.y + box.height / 2; // above the point there, below it near the top
    dragLayer.replaceChildren(
      svgEl(
        "text",
        {
          class: "drop-hint",
          "data-testid": "drop-hint",
          x: x + (right ? -1 : 1) * width * 3,
          y: low ? y - width * 3 : y + width * 8,
          "font-size": width * 5,
          "stroke-width": width * 1.2,
          "text-anchor": right ? "end" : "start",
        },
        "No object here: F floor, W wall, C ceiling",
      ),
    );
    window.clearTimeout(hintTimer);
    hintTimer = window.setTimeout(() => dragLayer.replaceChildren(), DROP_HINT_MS);
  };
  const onDown = (event: PointerEvent) => {
    const child = event.button === 0 && session.editable ? arrowAt(event) : null;
    if (!child) return;
    press = { child, x: event.clientX, y: event.clientY, dragging: false };
    window.addEventListener("pointermove", onMove);
    window.addEventListener("pointerup", onUp);
  };

  svg.addEventListener("click", onClick);
  svg.addEventListener("pointerdown", onDown);
  svg.addEventListener("mousemove", onHover);
  svg.addEventListener("mouseleave", clearPreview);
  const unsubscribe = session.subscribe((change) => {
    // A locked scene ends the pick (another selection ends it in the session).
    if (change === "lock") arm(null);
    if (change === "select") {
      svg.classList.toggle("is-picking", session.picking !== null);
      if (armedChild() === null) clearPreview();
    }
  });
  const removeKey = registerShortcut({
    keys: PICK_SUPPORTER_KEY,
    description: "Pick the selected object's supporter: then click the object that holds it up",
    scope: "Support editing",
    enabled: () => session.editable,
    run: () => {
      const child = session.selected;
      arm(child);
      session.say(
        child
          ? `Click the object that holds up ${child} (or press F, W or C; Esc cancels).`
          : "Select an arrow or object first (click it).",
      );
    },
  });
  return () => {
    window.clearTimeout(hintTimer);
    unsubscribe();
    removeKey();
    svg.removeEventListener("click", onClick);
    svg.removeEventListener("pointerdown", onDown);
    svg.removeEventListener("mousemove", onHover);
    svg.removeEventListener("mouseleave", clearPreview);
    window.removeEventListener("pointermove", onMove);
    window.removeEventListener("pointerup", onUp);
    dragLayer.remove();
  };
}
