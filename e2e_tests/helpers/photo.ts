// Driving the photo like an annotator: click an arrow, click an object, drag an arrowhead.
// Points are found on the page (on the arrow's own shaft, inside the object's mask and not
// under an arrow), so clicks land where a person would click.
import path from "node:path";
import { expect, type Page } from "@playwright/test";

export async function openScene(page: Page, sceneId: string): Promise<void> {
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("object-table")).toBeVisible();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
}

export async function setAuthor(page: Page, name: string): Promise<void> {
  const input = page.getByTestId("author-input");
  await input.fill(name);
  await input.press("Tab");
  await input.blur();
}

/** Keep autosave from firing during a test that watches unsaved state (set before goto). */
export async function slowAutosave(page: Page, ms = 600_000): Promise<void> {
  await page.addInitScript((delay) => {
    localStorage.setItem("holiscene.autosaveDelayMs", String(delay));
  }, ms);
}

/** The model has scored the scene (live suggestions are ready). */
export async function waitForModel(page: Page): Promise<void> {
  await expect(page.getByTestId("suggestion-status")).toContainText(/objects? scored in/, {
    timeout: 90_000,
  });
}

/** A screen point on the arrow of `child` where the arrow itself is on top. */
export async function arrowPoint(
  page: Page,
  child: string,
  where: "shaft" | "head" = "shaft",
): Promise<{ x: number; y: number }> {
  const point = await page.evaluate(
    ({ child, where }) => {
      const group = document.querySelector(`.arrow[data-child="${child}"]`);
      const shaft = group?.querySelector<SVGPathElement>(".arrow-shaft");
      const svg = shaft?.ownerSVGElement;
      const matrix = shaft?.getScreenCTM();
      if (!group || !shaft || !svg || !matrix) return null;
      const length = shaft.getTotalLength();
      const fractions =
        where === "head" ? [0.98, 0.95, 0.9, 0.85] : [0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8, 0.9];
      // Other objects' centres (where their arrows' heads are): a click there is about that
      // object, not this arrow.
      const centres = [...document.querySelectorAll<SVGGraphicsElement>(".arrow-head")]
        .filter((head) => head.closest(".arrow") !== group)
        .map((head) => {
          const box = head.getBoundingClientRect();
          return [box.x + box.width / 2, box.y + box.height / 2] as const;
        });
      const clear = (x: number, y: number) =>
        where === "head" || centres.every(([cx, cy]) => Math.hypot(cx - x, cy - y) > 16);
      for (const f of fractions) {
        const p = shaft.getPointAtLength(length * f);
        const s = new DOMPoint(p.x, p.y).matrixTransform(matrix);
        const hit = document.elementFromPoint(s.x, s.y);
        if (hit?.closest(".arrow") === group && clear(s.x, s.y)) return { x: s.x, y: s.y };
      }
      return null;
    },
    { child, where },
  );
  if (!point) throw new Error(`no clickable point on the arrow of ${child}`);
  return point;
}

export async function clickArrow(page: Page, child: string): Promise<void> {
  const { x, y } = await arrowPoint(page, child);
  await page.mouse.click(x, y);
}

/**
 * A screen point inside `id`'s mask, not under an arrow or label, that the photo resolves to
 * `id` (its mask lights up when hovered there).
 */
export async function objectPoint(page: Page, id: string): Promise<{ x: number; y: number }> {
  const candidates = await page.evaluate((id) => {
    const mask = document.querySelector<SVGGraphicsElement>(`[data-testid="mask-${id}"]`);
    const svg = mask?.ownerSVGElement;
    const matrix = mask?.getScreenCTM();
    if (!mask || !svg || !matrix) return [];
    const box = mask.getBBox();
    const points: { x: number; y: number }[] = [];
    for (const fy of [0.5, 0.35, 0.65, 0.25, 0.75, 0.15, 0.85]) {
      for (const fx of [0.5, 0.35, 0.65, 0.25, 0.75, 0.15, 0.85]) {
        const p = new DOMPoint(box.x + box.width * fx, box.y + box.height * fy).matrixTransform(
          matrix,
        );
        const hit = document.elementFromPoint(p.x, p.y);
        if (hit && !hit.closest(".arrow, .unsupported-flag, .anchor"))
          points.push({ x: p.x, y: p.y });
      }
    }
    return points;
  }, id);
  for (const point of candidates) {
    await page.mouse.move(point.x, point.y);
    const hovered = await page
      .getByTestId(`mask-${id}`)
      .evaluate((node) => node.classList.contains("is-hovered"));
    if (hovered) return point;
  }
  throw new Error(`no point of ${id}'s mask resolves to it`);
}

export async function clickObject(page: Page, id: string): Promise<void> {
  const { x, y } = await objectPoint(page, id);
  await page.mouse.click(x, y);
}

/** Drag the arrowhead of `child` onto object `target`. */
export async function dragArrowTo(page: Page, child: string, target: string): Promise<void> {
  const to = await objectPoint(page, target);
  const from = await arrowPoint(page, child, "head");
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2, { steps: 4 });
  await page.mouse.move(to.x, to.y, { steps: 4 });
  await expect(page.getByTestId("drag-line")).toHaveCount(1);
  await page.mouse.up();
}

/** The arrow of an object as drawn: supporter, type, and whether it is a suggestion. */
export async function arrowOf(
  page: Page,
  child: string,
): Promise<{ parent: string; type: string; suggested: boolean; source: string } | null> {
  const arrow = page.getByTestId(`arrow-${child}`);
  if ((await arrow.count()) === 0) return null;
  return arrow.evaluate((node) => {
    const d = (node as SVGGElement).dataset;
    return {
      parent: d.parent ?? "",
      type: d.type ?? "",
      suggested: d.suggested === "true",
      source: d.source ?? "",
    };
  });
}

/** Every arrow on the photo: child -> what it shows (a suggestion counts: it is what is seen). */
export function shownGraph(page: Page): Promise<Record<string, { parent: string; type: string }>> {
  return page.getByTestId("arrow-layer").evaluate((layer) => {
    const graph: Record<string, { parent: string; type: string }> = {};
    for (const a of layer.querySelectorAll<SVGGElement>(".arrow[data-child]")) {
      graph[a.dataset.child ?? ""] = { parent: a.dataset.parent ?? "", type: a.dataset.type ?? "" };
    }
    return graph;
  });
}

/** Fill the scene list's upload form with a synthetic folder's photo, K, boxes and depth. */
export async function fillUploadWithDepth(page: Page, dir: string, name: string): Promise<void> {
  await page.getByTestId("upload-image").setInputFiles(path.join(dir, "img.png"));
  await page.getByTestId("upload-cam_k").setInputFiles(path.join(dir, "cam_K.txt"));
  await page.getByTestId("upload-detections").setInputFiles(path.join(dir, "detections.json"));
  await page.getByTestId("upload-depth").setInputFiles(path.join(dir, "depth.png"));
  await page.getByTestId("upload-name").fill(name);
}

/** Submit the scene list's upload form and wait until the photo's pipeline has finished. */
export async function submitUploadAndWait(page: Page): Promise<void> {
  await page.getByTestId("upload-submit").click();
  await expect(page.getByTestId("upload-job-progress")).toHaveAttribute(
    "data-status",
    "succeeded",
    { timeout: 120_000 },
  );
}
