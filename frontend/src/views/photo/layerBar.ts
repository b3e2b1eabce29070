// The row under the photo: a checkbox (and key) per overlay layer and the mask style controls;
// for a photo with depth, a checkbox that shows the depth over it. Beside the legends, as how
// the photo is drawn; above the photo it pushed the photo down a line.
import { el } from "../../dom";
import { registerShortcut } from "../../shortcuts";
import { maskStyleControls } from "./maskStyle";
import type { PhotoLayers } from "./photoSvg";

function toggle(label: string, testid: string, onChange: (on: boolean) => void, on = true) {
  const input = el("input", {
    testid,
    attrs: { type: "checkbox", checked: on },
    on: { change: () => onChange(input.checked) },
  });
  return { input, label: el("label", { className: "toggle" }, input, label) };
}

export function arrowLegend(): HTMLElement {
  const item = (className: string, text: string) =>
    el(
      "span",
      { className: "legend-item" },
      el("span", { className: `swatch ${className}` }),
      text,
    );
  return el(
    "div",
    { className: "legend", testid: "arrow-legend", attrs: { "aria-label": "Arrow colours" } },
    item("swatch--below", "supported from below"),
    item("swatch--behind", "from behind"),
    item("swatch--floor", "floor"),
    item("swatch--pending", "not saved"),
    item("swatch--doubtful", "a guess under 50%"),
    item("swatch--suggested", "suggested by the model"),
  );
}

/** `onDepth` hears when the depth overlay is shown or hidden (its key follows it). */
export function layerBar(
  layers: PhotoLayers,
  depthKey?: { show(on: boolean): void; element: HTMLElement },
): { element: HTMLElement; dispose(): void } {
  const setLayer = (layer: SVGGElement) => (on: boolean) => {
    layer.style.display = on ? "" : "none";
  };
  const layerToggles = [
    { key: "M", name: "masks", ...toggle("Masks", "toggle-masks", setLayer(layers.masks)) },
    { key: "H", name: "arrows", ...toggle("Arrows", "toggle-arrows", setLayer(layers.arrows)) },
    { key: "L", name: "labels", ...toggle("Labels", "toggle-labels", setLayer(layers.labels)) },
  ];
  const removeKeys = layerToggles.map(({ key, name, input }) =>
    registerShortcut({
      keys: key,
      description: `Hide or show the ${name}`,
      scope: "Photo",
      run: () => input.click(),
    }),
  );
  const styleControls = maskStyleControls();
  // Off at first: the depth hides the photo's colours.
  const showDepth = layers.depth && setLayer(layers.depth);
  const depth =
    showDepth &&
    toggle(
      "Depth",
      "toggle-depth",
      (on) => {
        showDepth(on);
        depthKey?.show(on);
      },
      false,
    );
  const element = el(
    "div",
    { className: "photo-toolbar photo-view-options", testid: "photo-view-options" },
    ...layerToggles.map((t) => t.label),
    depth?.label,
    // Beside its toggle, not over the photo, where it would hide labels and masks.
    depth && depthKey?.element,
    styleControls.element,
  );
  return {
    element,
    dispose() {
      styleControls.dispose();
      for (const remove of removeKeys) remove();
    },
  };
}
