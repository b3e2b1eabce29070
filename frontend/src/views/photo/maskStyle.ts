// How the masks look on the photo: coloured by object (default) or by class, and how opaque.
// Remembered in this browser; the photo and the object list follow changes at once.
import { el } from "../../dom";
import { browserStorage } from "../../state/browserStorage";
import type { Colouring } from "../objectColors";

export interface MaskStyle {
  colouring: Colouring;
  /** Opacity of the masks, 0.05..1 (hovering dims the others, selecting raises one). */
  opacity: number;
}

export const DEFAULT_MASK_STYLE: MaskStyle = { colouring: "object", opacity: 0.42 };
const KEY = "holiscene.maskStyle";
const MIN_OPACITY = 0.05;

/** A stored style, with anything missing or out of range taken from the default. */
function parseStyle(text: string | null): MaskStyle {
  let stored: Partial<MaskStyle> = {};
  try {
    stored = text ? (JSON.parse(text) as Partial<MaskStyle>) : {};
  } catch {
    // unreadable: the default
  }
  const colouring = stored.colouring === "class" ? "class" : "object";
  const opacity =
    typeof stored.opacity === "number" && Number.isFinite(stored.opacity)
      ? Math.min(1, Math.max(MIN_OPACITY, stored.opacity))
      : DEFAULT_MASK_STYLE.opacity;
  return { colouring, opacity };
}

export class MaskStyleSetting {
  private style: MaskStyle;
  private readonly listeners = new Set<(style: MaskStyle) => void>();

  constructor(private readonly storage: Storage | null = browserStorage()) {
    this.style = parseStyle(storage?.getItem(KEY) ?? null);
  }

  get(): MaskStyle {
    return this.style;
  }

  set(change: Partial<MaskStyle>): void {
    this.style = parseStyle(JSON.stringify({ ...this.style, ...change }));
    try {
      this.storage?.setItem(KEY, JSON.stringify(this.style));
    } catch {
      // not remembered: this page only
    }
    for (const listener of this.listeners) listener(this.style);
  }

  subscribe(listener: (style: MaskStyle) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }
}

/** The one setting of this page (the photo's controls and the object list share it). */
export const maskStyle = new MaskStyleSetting();

/** The photo toolbar's controls: colouring (select) and opacity (slider). */
export function maskStyleControls(setting: MaskStyleSetting = maskStyle): {
  element: HTMLElement;
  dispose: () => void;
} {
  const colouring = el(
    "select",
    {
      testid: "mask-colouring",
      attrs: { "aria-label": "Colour the masks", title: "Colour the masks by object or by class" },
      on: { change: () => setting.set({ colouring: colouring.value as Colouring }) },
    },
    el("option", { text: "by object", attrs: { value: "object" } }),
    el("option", { text: "by class", attrs: { value: "class" } }),
  );
  const opacity = el("input", {
    testid: "mask-opacity",
    attrs: {
      type: "range",
      min: MIN_OPACITY,
      max: 1,
      step: 0.01,
      "aria-label": "Mask opacity",
      title: "How opaque the masks are",
    },
    on: { input: () => setting.set({ opacity: opacity.valueAsNumber }) },
  });
  const show = ({ colouring: c, opacity: o }: MaskStyle) => {
    colouring.value = c;
    opacity.value = String(o);
  };
  show(setting.get());
  const element = el(
    "span",
    { className: "mask-style" },
    el("label", { className: "toggle" }, "Colour", colouring),
    el("label", { className: "toggle" }, "Opacity", opacity),
  );
  return { element, dispose: setting.subscribe(show) };
}
