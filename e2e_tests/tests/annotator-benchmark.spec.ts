// Benchmark: a scripted annotator fixes the predicted support graphs of synthetic scenes whose
// truth is known (`holiscene synth` writes gt.json). Targets (issue 6): a graph with k wrong
// edges is fixed in at most 2k + 1 user actions, a fully correct one accepted in one; an edit
// redraws its arrow within 50 ms.
//
// Scenes: some imported as generated (the pipeline's Relation Network is rarely wrong on them),
// some with one supporting object's detected class changed to "pillow", as a detector's
// mistake would, so that the network gets several edges wrong (k counted at run time against
// gt.json). The annotator works as a person would: it looks at the arrows on the photo (the
// model's live suggestions included), picks the first wrong one, clicks it (or the "?" flag
// of an object without one), then clicks the true supporter (or presses F / W / C for floor,
// wall, ceiling) and T if the type is still wrong; when every arrow is right it presses Shift+A once to accept the rest. Every click and
// key press counts as one action (pointer moves do not). Autosave stores the result, which
// must equal the truth, every edge set by a person.
//
// Edit-to-arrow time: from the input event's timestamp (the click or key press that makes the
// edit) to the moment the arrow's SVG element shows the new supporter (a MutationObserver),
// and to the next animation frame after it; medians over all edits.
import { cpSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import type { SupportRelation } from "@holiscene/schema";
import { expect, type Page, test } from "@playwright/test";
import { getScene } from "../helpers/api";
import {
  clickArrow,
  clickObject,
  openScene,
  setAuthor,
  shownGraph,
  waitForModel,
} from "../helpers/photo";
import { scratchDir } from "../helpers/scratch";
import { importSynthetic, type SyntheticScene, synthesize, wrongEdges } from "../helpers/synthetic";

const TARGET_MS = 50;
const STRUCTURAL_KEYS: Record<string, string> = { floor: "f", wall: "w", ceiling: "c" };
// Seeds chosen once for a mix: 700, 703, 706 as generated; 701, 704, 705, 707 relabelled.
const AS_GENERATED = [700, 703, 706];
const RELABELLED = [701, 704, 705, 707];

interface Timing {
  /** The arrow's SVG element shows the edit. */
  dom: number;
  /** The next animation frame began (the frame that paints the change). */
  frame: number;
}

interface SceneFigures {
  name: string;
  objects: number;
  k: number;
  actions: number;
  /** Objects the annotator corrected (the rest of the k came right by themselves). */
  corrected: number;
  /** Suggestions on the photo before the first action. */
  suggestedAtStart: number;
  times: Timing[];
}

/** A copy of the scene whose first supporting object is detected as a pillow. */
function relabelled(scene: SyntheticScene): SyntheticScene {
  const dir = scratchDir("holiscene-relabelled-");
  cpSync(scene.dir, dir, { recursive: true });
  const file = path.join(dir, "detections.json");
  const detections = JSON.parse(readFileSync(file, "utf8")) as { class: string }[];
  const supporters = [...new Set(scene.truth.map((s) => s.parent))]
    .filter((p) => /^o\d+$/.test(p))
    .sort((a, b) => Number(a.slice(1)) - Number(b.slice(1)));
  const first = supporters[0];
  const detection = first ? detections[Number(first.slice(1))] : undefined;
  if (detection) detection.class = "pillow";
  writeFileSync(file, JSON.stringify(detections));
  return { dir, truth: scene.truth };
}

/** Arm the timer: it stops when `child`'s arrow shows `parent` (and `type`, if given). */
async function armTimer(page: Page, child: string, parent: string, type: string | null) {
  await page.evaluate(
    ({ child, parent, type }) => {
      const w = window as unknown as { __hsTiming?: Promise<{ dom: number; frame: number }> };
      const layer = document.querySelector('[data-testid="arrow-layer"]');
      if (!layer) throw new Error("no arrow layer");
      let start: number | null = null;
      const mark = (event: Event) => {
        start ??= event.timeStamp;
      };
      addEventListener("click", mark, true);
      addEventListener("keydown", mark, true);
      const shows = () => {
        const a = layer.querySelector<SVGGElement>(`.arrow[data-child="${child}"]`);
        return a?.dataset.parent === parent && (type === null || a.dataset.type === type);
      };
      w.__hsTiming = new Promise((resolve) => {
        const observer = new MutationObserver(() => {
          if (start === null || !shows()) return;
          const began = start;
          const dom = performance.now() - began;
          observer.disconnect();
          removeEventListener("click", mark, true);
          removeEventListener("keydown", mark, true);
          requestAnimationFrame(() => resolve({ dom, frame: performance.now() - began }));
        });
        observer.observe(layer, { childList: true, subtree: true, attributes: true });
      });
    },
    { child, parent, type },
  );
}

const readTimer = (page: Page) =>
  page.evaluate(() => (window as unknown as { __hsTiming: Promise<Timing> }).__hsTiming);

/** Fix the scene as a person would, counting actions; returns them with the edit times. */
async function annotate(
  page: Page,
  truth: readonly SupportRelation[],
  k: number,
): Promise<{ actions: number; corrected: number; times: Timing[] }> {
  let actions = 0;
  const corrected = new Set<string>();
  const times: Timing[] = [];
  const act = async (action: () => Promise<void>) => {
    await action();
    actions += 1;
  };
  const timed = async (
    child: string,
    parent: string,
    type: string | null,
    key: () => Promise<void>,
  ) => {
    await armTimer(page, child, parent, type);
    await act(key);
    times.push(await readTimer(page));
  };
  for (let guard = 0; guard < 4 * k + 10; guard++) {
    const shown = await shownGraph(page);
    const wrong = truth.find(
      (t) => shown[t.child]?.parent !== t.parent || shown[t.child]?.type !== t.type,
    );
    if (!wrong) break;
    const { child, parent, type } = wrong;
    corrected.add(child);
    const now = shown[child];
    // The arrow, or the "?" flag of an object without one: either arms the pick.
    if (now) await act(() => clickArrow(page, child));
    else await act(() => page.getByTestId(`unsupported-${child}`).click());
    if (now?.parent !== parent) {
      const key = STRUCTURAL_KEYS[parent];
      await timed(child, parent, null, () =>
        key ? page.keyboard.press(key) : clickObject(page, parent),
      );
    }
    if ((await shownGraph(page))[child]?.type !== type) {
      await timed(child, parent, type, () => page.keyboard.press("t"));
    }
  }
  await act(() => page.keyboard.press("Shift+A"));
  return { actions, corrected: corrected.size, times };
}

const median = (values: number[]) => {
  const sorted = [...values].sort((a, b) => a - b);
  const mid = Math.floor(sorted.length / 2);
  return sorted.length % 2
    ? (sorted[mid] as number)
    : ((sorted[mid - 1] as number) + (sorted[mid] as number)) / 2;
};

test("a graph with k wrong edges is fixed in at most 2k + 1 actions; edits redraw within 50 ms", async ({
  page,
  request,
}, testInfo) => {
  test.setTimeout(20 * 60_000);
  const scenes = [
    ...AS_GENERATED.map((seed) => ({ seed, scene: synthesize(seed, 1)[0], changed: false })),
    ...RELABELLED.map((seed) => ({ seed, scene: synthesize(seed, 1)[0], changed: true })),
  ];
  const figures: SceneFigures[] = [];
  await page.goto("/");
  await setAuthor(page, "benchmark");
  for (const { seed, scene, changed } of scenes) {
    if (!scene) throw new Error(`no synthetic scene for seed ${seed}`);
    const input = changed ? relabelled(scene) : scene;
    const name = `synth-${seed}${changed ? " (a supporter detected as a pillow)" : ""}`;
    const doc = await importSynthetic(request, input, name);
    const ids = (doc.scene.objects ?? []).map((o) => o.id).sort();
    expect(ids).toEqual(scene.truth.map((t) => t.child).sort());
    const k = wrongEdges(doc, scene.truth).length;

    await openScene(page, doc.scene_id);
    await waitForModel(page);
    const suggestedAtStart = await page.locator(".arrow[data-suggested='true']").count();
    const { actions, corrected, times } = await annotate(page, scene.truth, k);
    await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved", {
      timeout: 30_000,
    });
    const saved = await getScene(request, doc.scene_id);
    const graph = new Map((saved.scene.supports ?? []).map((s) => [s.child, s]));
    for (const t of scene.truth) {
      expect(graph.get(t.child), `${name}: ${t.child}`).toMatchObject({
        parent: t.parent,
        type: t.type,
        source: "manual",
        author: "benchmark",
      });
    }
    expect(graph.size).toBe(scene.truth.length);
    figures.push({
      name,
      objects: scene.truth.length,
      k,
      actions,
      corrected,
      suggestedAtStart,
      times,
    });
  }

  const lines = figures.map(
    (f) =>
      `  ${f.name}: ${f.objects} objects, k = ${f.k} wrong, ${f.actions} actions ` +
      `(2k + 1 = ${2 * f.k + 1})${f.actions <= 2 * f.k + 1 ? "" : "  OVER"}; ` +
      `${f.corrected} corrected by hand, ${f.k - f.corrected} by the live suggestions ` +
      `(${f.suggestedAtStart} shown at the start)`,
  );
  const all = figures.flatMap((f) => f.times);
  const k = figures.reduce((sum, f) => sum + f.k, 0);
  const actions = figures.reduce((sum, f) => sum + f.actions, 0);
  const bound = figures.reduce((sum, f) => sum + 2 * f.k + 1, 0);
  const dom = all.map((t) => t.dom);
  const frame = all.map((t) => t.frame);
  const report = [
    "annotator benchmark (synthetic scenes, truth from gt.json):",
    ...lines,
    `  total: ${actions} actions for ${k} wrong edges in ${figures.length} scenes (sum of 2k + 1 = ${bound})`,
    `  edit to redrawn arrow (SVG updated) over ${all.length} edits: median ${median(dom).toFixed(1)} ms, ` +
      `max ${Math.max(...dom).toFixed(1)} ms (target ${TARGET_MS} ms)`,
    `  edit to the next animation frame (the whole page rendered; the 3D panel uses software WebGL here): ` +
      `median ${median(frame).toFixed(1)} ms, max ${Math.max(...frame).toFixed(1)} ms`,
  ].join("\n");
  console.log(report);
  await testInfo.attach("annotator-benchmark.txt", { body: report, contentType: "text/plain" });

  for (const f of figures) {
    expect(f.actions, `${f.name}: actions for k = ${f.k}`).toBeLessThanOrEqual(2 * f.k + 1);
  }
  expect(
    figures.some((f) => f.k === 0),
    "a fully correct scene among them",
  ).toBe(true);
  expect(
    figures.some((f) => f.k >= 2),
    "a scene with several wrong edges among them",
  ).toBe(true);
  expect(all.length).toBeGreaterThan(0);
  expect(median(dom)).toBeLessThanOrEqual(TARGET_MS);
});
