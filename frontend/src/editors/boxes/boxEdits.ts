// What a finished box becomes: a new object (its class picked beside the box, then one
// add_object edit; the server cuts its mask) or a moved or resized box (one set_bbox edit).
// While an edit is on its way its box stays drawn (`sending`).

import { classText } from "../../state/classNames";
import { classHints } from "../../views/scene/classHints";
import { cancelClassPicker, pickClass } from "../../views/scene/classPicker";
import { type Box, type Grip, roundBox } from "../boxGeometry";
import type { PhotoToolHost } from "../photoTools";

/** "chair d3" */
export const objectName = (object: { id: string; class: string }) =>
  `${classText(object.class)} ${object.id}`;

/** The rectangle of an image-pixel box on the screen (client pixels). */
export function screenRect(svg: SVGSVGElement, box: readonly number[]) {
  const matrix = svg.getScreenCTM();
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  const a = new DOMPoint(x1, y1).matrixTransform(matrix ?? undefined);
  const b = new DOMPoint(x2, y2).matrixTransform(matrix ?? undefined);
  return { left: a.x, top: a.y, right: b.x, bottom: b.y };
}

/** The class a box gets when the page is left before its class was chosen. */
const UNCHOSEN_CLASS = "otherprop";

export class BoxEdits {
  /** Boxes sent and not yet in a revision (drawn until the answer comes). */
  readonly sending = new Map<string, Box>();
  /** The page is going: a box waiting for its class stays in the drafts. */
  private leaving = false;

  /** `redraw` is told whenever `sending` changes. */
  constructor(
    private readonly host: PhotoToolHost,
    private readonly redraw: () => void,
  ) {}

  /** Ask for the new object's class, then add it (selected once drawn, and once saved). */
  async addObject(box: Box): Promise<void> {
    const { host, sending, redraw } = this;
    const { session, objects: editor } = host;
    const key = `new-${Date.now()}`;
    sending.set(key, box);
    redraw();
    const near = screenRect(host.svg, box);
    const [id = "d1"] = editor.newObjectIds(1);
    // Kept in the drafts while its class is picked: a page left (Back, a link, the tab
    // closed) before the pick offers the box on the next visit, as an object action not saved.
    const kept = this.keepWhilePicking(id, box);
    const cls = await pickClass({
      near,
      title: "Class of the new object",
      objects: session.objects,
      likely: classHints.at(session.sceneId, box),
    });
    if (kept && !this.leaving) session.drafts.saveFailedAction(session.sceneId, null);
    if (!cls) {
      sending.delete(key);
      redraw();
      return;
    }
    // Selected as soon as it is drawn (before the server answers), so a key pressed at once
    // (F: on the floor) is for it; after the other listeners have seen the new revision.
    const stopWatching = session.subscribe((change) => {
      if (change !== "document" || !session.object(id)) return;
      stopWatching();
      queueMicrotask(() => {
        if (session.object(id)) session.select(id);
      });
    });
    const saved = await editor.apply(
      [{ kind: "add_object", id, class: cls, bbox: roundBox(box), source: "manual" }],
      `add ${objectName({ id, class: cls })}`,
    );
    stopWatching();
    sending.delete(key);
    // Selected when saved under its id (a conflict may have given it another).
    if (saved) session.select(session.object(id) ? id : null);
    else if (session.selected === id && !session.object(id)) session.select(null);
    redraw();
  }

  /** Put the box in the drafts as an action not saved; false when one is there already (the
   * drafts keep one, which is not overwritten). */
  private keepWhilePicking(id: string, box: Box): boolean {
    const { session } = this.host;
    if (session.drafts.loadFailedAction(session.sceneId)) return false;
    session.drafts.saveFailedAction(session.sceneId, {
      label: `add ${objectName({ id, class: UNCHOSEN_CLASS })}`,
      message:
        "the page was left while this box's class was being picked; Retry adds it and asks " +
        "its class again",
      edits: [
        { kind: "add_object", id, class: UNCHOSEN_CLASS, bbox: roundBox(box), source: "manual" },
      ],
      failedAt: new Date().toISOString(),
      madeOn: session.doc.revision,
      classToPick: id,
    });
    return true;
  }

  /** The page is going: a class picker open for a new box closes, and the box stays in the
   * drafts for the next visit. */
  leave(): void {
    this.leaving = true;
    cancelClassPicker();
  }

  /** Give the object its moved (grip "move") or resized box. */
  async setBox(id: string, box: Box, grip: Grip): Promise<void> {
    const { host, sending, redraw } = this;
    const object = host.session.object(id);
    if (!object) return;
    sending.set(id, box);
    redraw();
    const what = grip === "move" ? "move" : "resize";
    await host.objects.apply(
      [{ kind: "set_bbox", id, bbox: roundBox(box) }],
      `${what} the box of ${objectName(object)}`,
    );
    sending.delete(id);
    redraw();
  }
}
