// The brush size shared by Brush, Eraser and Refine: a slider, and [ ] to step it.
import { el } from "../../dom";

export const SMALLER_KEY = "[";
export const LARGER_KEY = "]";

/** Brush sizes: the diameter in photo pixels. */
const MIN_SIZE = 2;
const MAX_SIZE = 160;
const DEFAULT_SIZE = 16;
const SIZE_STEP = 1.25;

/** The brush size shared by Brush, Eraser and Refine: a slider, and [ ] to step it. */
export class BrushSize {
  size = DEFAULT_SIZE;
  readonly input = el("input", {
    testid: "brush-size",
    attrs: {
      type: "range",
      min: MIN_SIZE,
      max: MAX_SIZE,
      step: 1,
      value: DEFAULT_SIZE,
      "aria-label": "Brush size in photo pixels",
      title: `Brush size in photo pixels (${SMALLER_KEY} smaller, ${LARGER_KEY} larger)`,
    },
    on: { input: () => this.set(Number(this.input.value)) },
  });
  private readonly value = el("span", {
    className: "brush-size-value",
    testid: "brush-size-value",
  });
  readonly element = el("label", { className: "brush-size" }, "Size", this.input, this.value);
  private readonly listeners = new Set<() => void>();

  constructor() {
    this.set(DEFAULT_SIZE);
  }

  get radius(): number {
    return this.size / 2;
  }

  set(size: number): void {
    this.size = Math.round(Math.min(MAX_SIZE, Math.max(MIN_SIZE, size)));
    this.input.value = String(this.size);
    this.value.textContent = `${this.size} px`;
    for (const listener of this.listeners) listener();
  }

  step(up: boolean): void {
    const next = up ? this.size * SIZE_STEP : this.size / SIZE_STEP;
    // At small sizes a factor would round back to the same size.
    this.set(up ? Math.max(next, this.size + 1) : Math.min(next, this.size - 1));
  }

  onChange(listener: () => void): void {
    this.listeners.add(listener);
  }
}
