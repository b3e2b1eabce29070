// The line under the photo: the selected edge with its provenance (who set it, when, or the
// model's confidence), what can be done next, and why the last action did nothing.
import { el } from "../dom";
import { classText } from "../state/classNames";
import type { SceneSession } from "../state/sceneSession";
import { implausibleBelow } from "../state/supportGraph";
import { provenanceText } from "../views/photo/arrowLayer";
import { unresolved } from "./supportActions";

export function mountEdgeInfo(container: HTMLElement, session: SceneSession): () => void {
  const edge = el("span", { className: "edge-info-edge", testid: "edge-info-edge" });
  const provenance = el("span", {
    className: "edge-info-provenance",
    testid: "edge-info-provenance",
  });
  const hint = el("span", { className: "edge-info-hint", testid: "edge-info-hint" });
  const doubt = el("span", { className: "edge-info-message", testid: "edge-info-doubt" });
  const message = el("span", {
    className: "edge-info-message",
    testid: "edit-message",
    attrs: { role: "status" },
  });
  container.replaceChildren(
    el(
      "div",
      { className: "edge-info", testid: "edge-info" },
      edge,
      provenance,
      doubt,
      hint,
      message,
    ),
  );

  const update = () => {
    const child = session.selected;
    const left = unresolved(session).length;
    const remaining =
      left === 0
        ? "every edge checked"
        : session.editable
          ? `${left} still to check (Shift+A accepts them as shown)`
          : `${left} not checked by anyone`;
    const shown = child ? session.displayed(child) : null;
    const object = child ? session.object(child) : undefined;
    doubt.textContent =
      (object && shown && implausibleBelow(object, session.object(shown.parent), shown.type)) || "";
    doubt.hidden = doubt.textContent === "";
    if (!child) {
      edge.textContent = "";
      provenance.textContent = "";
      hint.textContent = session.editable
        ? `Click an arrow to select it · ${remaining} · ? lists every key`
        : `Read only · click an arrow to see who set it · ${remaining} · ? lists every key`;
    } else {
      const name = `${child}${object ? ` (${classText(object.class)})` : ""}`;
      // A suggestion for an object without a supporter is not one yet: the list says "none".
      edge.textContent = !shown
        ? `${name}: no supporter`
        : shown.suggested && !shown.support
          ? `${name}: no supporter yet; the model suggests ${shown.parent}, ${shown.type} (A accepts)`
          : `${name} on ${shown.parent}, ${shown.type}`;
      const suggestion = session.suggestions().get(child);
      const was = shown?.support ?? session.savedSupport(child);
      provenance.textContent = shown
        ? provenanceText(shown.support, suggestion) +
          (suggestion && was ? ` (was ${was.parent}, ${was.type})` : "")
        : "";
      // What a click on another object does now: picks the supporter, or only selects.
      const pick =
        session.picking === child ? "click the new supporter" : "S then click the new supporter";
      hint.textContent = session.editable
        ? `${pick} (F floor, W wall, C ceiling) · A accept · R reject · T below/behind · Shift+Del no supporter · Del remove the object · Esc`
        : "read only: nothing can be changed now · Esc";
    }
    message.textContent = session.message ?? "";
    message.hidden = !session.message;
  };
  update();
  return session.subscribe((change) => {
    if (change !== "hover") update();
  });
}
