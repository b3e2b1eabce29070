// The models page's history: who made which model active, when.
import type { ModelEvent } from "@holiscene/schema";
import { el, formatTime } from "../../dom";

function eventItem(event: ModelEvent): HTMLLIElement {
  const what =
    event.action === "seed"
      ? `v${event.model_version} registered as the first model`
      : `${event.action === "rollback" ? "rolled back" : "promoted"} to v${event.model_version}` +
        (event.previous_version !== null ? ` (from v${event.previous_version})` : "");
  return el(
    "li",
    {},
    el("strong", { text: what }),
    ` by ${event.actor} · ${formatTime(event.at)}`,
    event.note ? ` · ${event.note}` : "",
  );
}

export interface ModelHistory {
  element: HTMLElement;
  show(events: ModelEvent[]): void;
}

export function modelHistory(): ModelHistory {
  const list = el("ol", { className: "model-history", testid: "model-history" });
  return {
    element: el(
      "section",
      { className: "card" },
      el("h2", { text: "History of the active model" }),
      list,
    ),
    show: (events) => list.replaceChildren(...events.map(eventItem)),
  };
}
