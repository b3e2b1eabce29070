// The depth overlay's key, beside the Depth toggle while the depth is shown: its colours as a
// bar from near to far with the depths (metres) at both ends, as GET .../depth-key gives them
// (the colours span the 2nd to 98th percentile of the depth present; nearer and further
// depths take the end colours).
import type { DepthKey } from "@holiscene/schema";
import { api } from "../../api/client";
import { el } from "../../dom";
import "./depthKey.css";

const metres = (value: number) => `${value.toFixed(value < 10 ? 2 : 1)} m`;

export function depthKey(sceneId: string): {
  element: HTMLElement;
  show(on: boolean): void;
  dispose(): void;
} {
  const bar = el("span", { className: "depth-key-bar", testid: "depth-key-bar" });
  const near = el("span", { className: "depth-key-end", testid: "depth-key-near" });
  const far = el("span", { className: "depth-key-end", testid: "depth-key-far" });
  const element = el(
    "div",
    { className: "depth-key", testid: "depth-key", attrs: { "aria-label": "Depth colours" } },
    el("span", { className: "depth-key-title", text: "Depth" }),
    near,
    bar,
    far,
  );
  element.hidden = true;
  const abort = new AbortController();
  let asked = false;
  const fill = (key: DepthKey) => {
    bar.style.background = `linear-gradient(to right, ${key.colours.join(", ")})`;
    near.textContent = `near ${metres(key.near_m)}`;
    far.textContent = `far ${metres(key.far_m)}`;
    element.title =
      `Red is ${metres(key.near_m)} from the camera or nearer, blue ${metres(key.far_m)} or ` +
      "further (along the camera's axis); transparent where the sensor saw nothing.";
    element.dataset.loaded = "true";
  };
  return {
    element,
    show(on) {
      element.hidden = !on;
      if (!on || asked) return;
      asked = true;
      near.textContent = "…";
      api.depthKey(sceneId, abort.signal).then(fill, (error: unknown) => {
        if (abort.signal.aborted) return;
        asked = false; // asked again next time
        near.textContent = `no key: ${error instanceof Error ? error.message : String(error)}`;
      });
    },
    dispose: () => abort.abort(),
  };
}
