// Editing objects on the photo like an annotator: choose a photo tool, draw or drag a box in
// image pixels (turned into screen points through the photo's own transform), pick a class.
import { expect, type Page } from "@playwright/test";

/** The screen point of image pixel (x, y) on the photo. */
export async function screenPoint(
  page: Page,
  x: number,
  y: number,
): Promise<{ x: number; y: number }> {
  return page.getByTestId("photo").evaluate(
    (svg, [x, y]) => {
      const matrix = (svg as SVGSVGElement).getScreenCTM();
      if (!matrix) throw new Error("the photo has no transform");
      const p = new DOMPoint(x, y).matrixTransform(matrix);
      return { x: p.x, y: p.y };
    },
    [x, y] as const,
  );
}

export async function chooseTool(page: Page, id: string): Promise<void> {
  await page.getByTestId(`photo-tool-${id}`).click();
  await expect(page.getByTestId(`photo-tool-${id}`)).toHaveAttribute("aria-pressed", "true");
}

/** Press at image point `from`, move to `to` in a few steps, release. */
export async function dragOnPhoto(
  page: Page,
  from: readonly [number, number],
  to: readonly [number, number],
): Promise<void> {
  const a = await screenPoint(page, from[0], from[1]);
  const b = await screenPoint(page, to[0], to[1]);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move((a.x + b.x) / 2, (a.y + b.y) / 2, { steps: 3 });
  await page.mouse.move(b.x, b.y, { steps: 3 });
  await page.mouse.up();
}

/** Type into the open class picker and pick its first line with Enter. */
export async function pickClass(page: Page, typed: string, expected: string): Promise<void> {
  const input = page.getByTestId("class-picker-input");
  await expect(input).toBeFocused();
  await input.fill(typed);
  await expect(page.getByTestId("class-option").first()).toHaveAttribute("data-name", expected);
  await input.press("Enter");
  await expect(page.getByTestId("class-picker")).toHaveCount(0);
}

/** The object editor has saved everything it was given. */
export async function objectEditsSaved(page: Page): Promise<void> {
  await expect(page.getByTestId("object-edit-status")).not.toHaveAttribute("data-state", "busy");
  await expect(page.getByTestId("object-edit-failure")).toBeHidden();
}
