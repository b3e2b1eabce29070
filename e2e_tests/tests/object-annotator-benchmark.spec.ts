// Benchmark: a scripted annotator turns a plain photo of a synthetic room (about 10 objects,
// truth from gt.json) into a full scene: boxes, classes, masks and supports. Targets (issue 19):
// at most 40 recorded actions without the detector's suggestions and at most 20 with them
// (asserted), every edit redrawn within 50 ms (reported: it hangs on the machine's load;
// figures in docs/benchmarks.md).
//
// The photo is imported with an empty detections.json: the pipeline still estimates the camera
// and the room, but there are no objects. The annotator works as a person would, with the
// truth standing in for their eyes:
// - Run 1 (no suggestions): the detector's boxes that appear by themselves on an empty scene
//   are dropped with "Reject all"; then B (box tool) and, for each true object, one drag from
//   a corner of its box to the opposite one, and its class in the picker (a digit when the
//   class is among the first nine lines, else a few letters typed, then Enter or a digit).
// - Run 2 (suggestions): Shift+Y accepts every suggested box; a suggestion matching no true
//   object is removed (click it, Delete), a wrong class changed (a click on the class in the
//   object list, then the picker), and the objects the detector missed are drawn as in run 1.
// - The picker lists first the classes the detector saw at the box (up to three, down to a
//   score of 10%: classHints.ts), then the most used; so a digit picks most classes, even of
//   a box drawn where the detector saw something too faintly to suggest it.
// - Masks: the server cuts each new object's mask (GrabCut); when it overlaps the true mask by
//   less than 0.5 the annotator refines it: K, one stroke over the object, then back.
// - Supports: V (select), then as in the support benchmark: the first wrong arrow is clicked,
//   then its true supporter (or F / W / C), T when the type is wrong; Shift+A accepts the rest.
// Every click, drag, typed word and key press counts as one action; pointer moves do not.
//
// Edit-to-redraw: from the input event that makes an edit (the last click, key press or
// pointer release before the page shows it) to the moment the page shows it (a MutationObserver
// on the page), and to the next animation frame. Object edits are saved at once. The page
// shows what it can foresee before the server answers (a class, a box, a removal, a new object
// by its box), so those are timed from the input; an edit it cannot foresee (a refined mask) is
// timed from the page getting the server's answer (its fetch resolving, which can be tens of ms
// after the network's responseEnd on a loaded machine) to the page showing it,
// and to the next animation frame (the photo painted with it). A new object's mask, cut by the
// server, is timed the same way ("answer drawn").
import { cpSync, existsSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import type { Mask, ModelInfo, Scene } from "@holiscene/schema";
import { type APIRequestContext, expect, type Page, type TestInfo, test } from "@playwright/test";
import { getScene } from "../helpers/api";
import { clickObject, openScene, setAuthor, shownGraph, waitForModel } from "../helpers/photo";
import {
  maskIou,
  maskPixels,
  matchObjects,
  type SceneScore,
  scoreScene,
} from "../helpers/sceneScore";
import { scratchDir } from "../helpers/scratch";
import { screenshotPath } from "../helpers/screenshots";
import { importSynthetic, synthesize } from "../helpers/synthetic";

const SEED = 1002;
const ACTIONS_WITHOUT = 40;
const ACTIONS_WITH = 20;
const TARGET_MS = 50;
const POOR_MASK = 0.5;
const STRUCTURAL_KEYS: Record<string, string> = { floor: "f", wall: "w", ceiling: "c" };
/** The objects drawn by their mask (an object shown by its box is a rect). */
const MASK_SHAPES = ".masks path[data-object]";
const FIGURES = path.resolve(import.meta.dirname, "../test-results/object-annotator-benchmark");

type Box = [number, number, number, number];

/** What the page must show for an edit to count as drawn (checked on every DOM change). */
type Shows =
  | { kind: "count"; selector: string; atLeast: number }
  | { kind: "attr"; selector: string; name: string; value: string }
  | { kind: "changed"; selector: string; name: string; from: string | null }
  | { kind: "text"; selector: string; text: string }
  | { kind: "gone"; selector: string };

interface Timing {
  what: string;
  /** Input event to the page showing the edit. */
  dom: number;
  /** Input event to the next animation frame after that. */
  frame: number;
  /**
   * The page getting the server's answer to it showing the edit (null: shown before any answer,
   * or no request, e.g. a support).
   */
  redraw: number | null;
  /** The server's answer to the next animation frame after the page showed it. */
  painted: number | null;
  /** Input event to the server's answer (its end on the network). */
  server: number | null;
  /**
   * For an edit shown before the server answers (a new object, by its box): the answer's
   * arrival to the page showing what it adds (the mask the server cut). Null otherwise.
   */
  answerDrawn: number | null;
}

interface Run {
  name: string;
  actions: number;
  log: string[];
  times: Timing[];
  masksFixed: number;
  score?: SceneScore;
  /** Suggestions the detector offered (run 2). */
  suggested?: number;
}

/** A copy of the synthetic folder with no boxes: the photo alone (with its intrinsics). */
function plainPhoto(seed: number) {
  const [scene] = synthesize(seed, 1);
  if (!scene) throw new Error(`no synthetic scene for seed ${seed}`);
  const dir = scratchDir("holiscene-plain-");
  cpSync(scene.dir, dir, { recursive: true });
  writeFileSync(path.join(dir, "detections.json"), "[]");
  const truth = JSON.parse(readFileSync(path.join(dir, "gt.json"), "utf8")) as Scene;
  return { scene: { dir, truth: scene.truth }, truth };
}

/** Remember the last input event and keep every request's timing (for the redraw figure). */
async function watchInput(page: Page): Promise<void> {
  await page.addInitScript(() => {
    const w = window as unknown as { __hsLastInput: number };
    w.__hsLastInput = 0;
    const mark = (event: Event) => {
      w.__hsLastInput = event.timeStamp;
    };
    // A menu's choice arrives as a change event, without a click or key press on the page.
    for (const type of ["pointerup", "click", "keydown", "change"])
      addEventListener(type, mark, true);
    performance.setResourceTimingBufferSize(100_000);
    // When the page's code gets each edit's answer (its fetch resolves, the small body with
    // it): the network's responseEnd comes earlier by the time the browser takes to hand it
    // over, which is not the page's.
    const received = window as unknown as { __hsAnswers: number[] };
    received.__hsAnswers = [];
    const send = window.fetch.bind(window);
    window.fetch = async (...args: Parameters<typeof fetch>) => {
      const response = await send(...args);
      const url = args[0] instanceof Request ? args[0].url : String(args[0]);
      if (/\/api\/scenes\/[^/]+\/edits$/.test(url)) received.__hsAnswers.push(performance.now());
      return response;
    };
  });
}

/**
 * Arm the timer for `shows` (and, when given, for `later`: what the server's answer adds, such
 * as a new object's mask after its box is shown at once); read it with readTimer after the action.
 */
async function armTimer(page: Page, shows: Shows, later: Shows | null): Promise<void> {
  await page.evaluate(
    ([shows, later]) => {
      const w = window as unknown as {
        __hsLastInput: number;
        __hsTiming?: Promise<{ start: number; dom: number; frame: number; later: number | null }>;
      };
      const armedAt = performance.now();
      const holds = (shows: Shows) => {
        const node = document.querySelector(shows.selector);
        switch (shows.kind) {
          case "count":
            return document.querySelectorAll(shows.selector).length >= shows.atLeast;
          case "attr":
            return node?.getAttribute(shows.name) === shows.value;
          case "changed":
            return node !== null && node.getAttribute(shows.name) !== shows.from;
          case "text":
            return node?.textContent === shows.text;
          case "gone":
            return node === null;
        }
      };
      w.__hsTiming = new Promise((resolve, reject) => {
        // Cleared only when settled: a frame that never comes fails the run here, not at the
        // test's timeout.
        const late = setTimeout(() => {
          observer.disconnect();
          const missing = dom === null ? shows : frame === 0 ? "an animation frame" : later;
          reject(new Error(`the page never showed ${JSON.stringify(missing)}`));
        }, 20_000);
        let dom: number | null = null;
        let frame = 0;
        let laterAt: number | null = null;
        const settle = () => {
          if (dom === null || frame === 0 || (later !== null && laterAt === null)) return;
          clearTimeout(late);
          resolve({ start: w.__hsLastInput, dom, frame, later: laterAt });
        };
        const observer = new MutationObserver(() => {
          if (w.__hsLastInput < armedAt) return;
          if (dom === null && holds(shows)) {
            const at = performance.now();
            dom = at;
            requestAnimationFrame(() => {
              frame = performance.now();
              settle();
            });
          }
          if (dom !== null && later !== null && laterAt === null && holds(later))
            laterAt = performance.now();
          if (dom !== null && (later === null || laterAt !== null)) {
            observer.disconnect();
            settle();
          }
        });
        observer.observe(document.body, {
          childList: true,
          subtree: true,
          attributes: true,
          characterData: true,
        });
      });
    },
    [shows, later] as const,
  );
}

async function readTimer(page: Page, what: string): Promise<Timing> {
  return page.evaluate(async (what) => {
    const w = window as unknown as {
      __hsTiming: Promise<{ start: number; dom: number; frame: number; later: number | null }>;
    };
    const { start, dom, frame, later } = await w.__hsTiming;
    // The edit's answer: the last one the page got after the input and before it showed the
    // edit (none when the page showed it before the answer); the network's end of it too.
    const last = (times: number[], until: number) => {
      const found = times.filter((t) => t >= start && t <= until);
      return found.length ? Math.max(...found) : null;
    };
    const received = (window as unknown as { __hsAnswers: number[] }).__hsAnswers;
    const networkEnds = performance
      .getEntriesByType("resource")
      .filter((e) => /\/api\/scenes\/[^/]+\/edits$/.test(e.name))
      .map((e) => (e as PerformanceResourceTiming).responseEnd);
    const answered = last(received, dom);
    const laterAnswered = later === null ? null : last(received, later);
    const networkEnd = last(networkEnds, dom) ?? (later === null ? null : last(networkEnds, later));
    // In a performance trace (HOLISCENE_TRACE_DIR), the redraw's span by the edit's name.
    performance.measure(`redraw: ${what}`, { start: answered ?? start, end: dom });
    performance.measure(`frame: ${what}`, { start: dom, end: frame });
    if (later !== null && laterAnswered !== null)
      performance.measure(`answer drawn: ${what}`, { start: laterAnswered, end: later });
    return {
      what,
      dom: dom - start,
      frame: frame - start,
      redraw: answered === null ? null : dom - answered,
      painted: answered === null ? null : frame - answered,
      server: networkEnd === null ? null : networkEnd - start,
      answerDrawn: later === null ? null : later - (laterAnswered ?? answered ?? start),
    };
  }, what);
}

/** A point of the photo (image pixels) on the screen. */
async function toScreen(page: Page, [x, y]: [number, number]): Promise<{ x: number; y: number }> {
  return page.locator("svg.photo-svg").evaluate(
    (svg, [x, y]) => {
      const p = new DOMPoint(x, y).matrixTransform(
        (svg as SVGSVGElement).getScreenCTM() ?? undefined,
      );
      return { x: p.x, y: p.y };
    },
    [x, y] as [number, number],
  );
}

/** The ids of the objects drawn on the photo. */
const shownObjects = (page: Page) =>
  page
    .getByTestId("mask-layer")
    .evaluate((layer) =>
      [...layer.querySelectorAll<SVGElement>("[data-object]")].map((n) => n.dataset.object ?? ""),
    );

const median = (values: number[]) => {
  if (values.length === 0) return Number.NaN;
  const sorted = [...values].sort((a, b) => a - b);
  const mid = Math.floor(sorted.length / 2);
  return sorted.length % 2
    ? (sorted[mid] as number)
    : ((sorted[mid - 1] as number) + (sorted[mid] as number)) / 2;
};

/** The annotator: every action it takes goes through `act`, which counts it. */
class Annotator {
  actions = 0;
  readonly log: string[] = [];
  readonly times: Timing[] = [];
  masksFixed = 0;
  /** True object id -> the id the app gave it. */
  readonly ids = new Map<string, string>();
  /** Screenshot file of the class picker the first time it opens (then null). */
  private pickerShot: string | null;

  constructor(
    readonly page: Page,
    readonly sceneId: string,
    readonly truth: Scene,
    name: string,
  ) {
    this.pickerShot = screenshotPath(`object-annotator-${name}-picker.png`);
  }

  async act(what: string, action: () => Promise<unknown>): Promise<void> {
    await action();
    this.actions += 1;
    this.log.push(what);
  }

  /** An action that makes an edit, timed until the page shows it. */
  async timed(
    what: string,
    shows: Shows,
    action: () => Promise<unknown>,
    later: Shows | null = null,
  ): Promise<void> {
    await armTimer(this.page, shows, later);
    await this.act(what, action);
    this.times.push(await readTimer(this.page, what));
  }

  async key(key: string, what = key): Promise<void> {
    await this.act(`key ${what}`, () => this.page.keyboard.press(key));
  }

  /** Draw `box` with the box tool: one drag between opposite corners, from one not on an object. */
  async drawBox(box: Box, label: string): Promise<void> {
    // Half a pixel inside: a press on the photo's very edge may land outside it.
    const [x1, y1, x2, y2] = [box[0] + 0.5, box[1] + 0.5, box[2] - 0.5, box[3] - 0.5];
    const corners: [[number, number], [number, number]][] = [
      [
        [x1, y1],
        [x2, y2],
      ],
      [
        [x2, y2],
        [x1, y1],
      ],
      [
        [x2, y1],
        [x1, y2],
      ],
      [
        [x1, y2],
        [x2, y1],
      ],
    ];
    const doc = await getScene(this.page.request, this.sceneId);
    const onObject = ([x, y]: [number, number]) =>
      (doc.scene.objects ?? []).some((o) => {
        const [px, py] = [Math.floor(x), Math.floor(y)];
        if (!o.mask) return x >= o.bbox[0] && x <= o.bbox[2] && y >= o.bbox[1] && y <= o.bbox[3];
        return maskPixels(o.mask, this.truth.image.width).has(py * this.truth.image.width + px);
      });
    // A press inside the selected object's box (or near its handles) moves or resizes it.
    const selectedId = await this.page
      .locator("tr.object-row.is-selected")
      .first()
      .getAttribute("data-object", { timeout: 1000 })
      .catch(() => null);
    const selected = (doc.scene.objects ?? []).find((o) => o.id === selectedId);
    const onSelected = ([x, y]: [number, number]) => {
      if (!selected) return false;
      const [x1, y1, x2, y2] = selected.bbox;
      return x >= x1 - 12 && x <= x2 + 12 && y >= y1 - 12 && y <= y2 + 12;
    };
    for (const [from, to] of corners) {
      if (onSelected(from)) continue;
      if ([-1, 0, 1].some((d) => onObject([from[0] + d, from[1] + d]))) continue;
      const start = await toScreen(this.page, from);
      const end = await toScreen(this.page, to);
      await this.page.mouse.move(start.x, start.y);
      await this.act(`drag a box for ${label}`, async () => {
        await this.page.mouse.down();
        await this.page.mouse.move((start.x + end.x) / 2, (start.y + end.y) / 2, { steps: 3 });
        await this.page.mouse.move(end.x, end.y, { steps: 3 });
        await this.page.mouse.up();
      });
      return;
    }
    throw new Error(`every corner of ${label}'s box is on another object`);
  }

  /**
   * Pick `cls` in the open class picker; the last key is the edit, timed until `shows`.
   * A digit when the class is listed in the first nine lines, else its first letters typed.
   */
  async pickClass(cls: string, shows: Shows, later: Shows | null = null): Promise<void> {
    const picker = this.page.getByTestId("class-picker");
    await expect(picker).toBeVisible();
    if (this.pickerShot) await this.page.screenshot({ path: this.pickerShot });
    this.pickerShot = null;
    const listed = () =>
      picker
        .getByTestId("class-option")
        .evaluateAll((nodes) => nodes.map((n) => (n as HTMLElement).dataset.name ?? ""));
    let options = await listed();
    let index = options.indexOf(cls);
    if (index < 0 || index >= 9) {
      const typed = cls.replaceAll("_", " ").slice(0, 3);
      await this.act(`type "${typed}"`, () => this.page.keyboard.type(typed));
      await expect.poll(async () => (await listed()).join()).not.toBe(options.join());
      options = await listed();
      index = options.indexOf(cls);
    }
    if (index < 0 || index >= 9) throw new Error(`${cls} is not among the picker's first lines`);
    // A digit picks its line; Enter only once something is typed (on a blank field the first
    // line, often a faint hint, is nobody's choice: the picker then says how to choose).
    const key = String(index + 1);
    await this.timed(`key ${key}: ${cls}`, shows, () => this.page.keyboard.press(key), later);
    await expect(picker).toBeHidden();
  }

  /** Draw a true object with the box tool (active) and give it its class. */
  async addObject(truthId: string): Promise<string> {
    const object = this.object(truthId);
    const before = await shownObjects(this.page);
    const masksBefore = await this.page.locator(MASK_SHAPES).count();
    await this.drawBox(object.bbox as Box, `${truthId} (${object.class})`);
    // Shown at once by its box; the mask the server cuts follows its answer.
    await this.pickClass(
      object.class,
      { kind: "count", selector: ".masks [data-object]", atLeast: before.length + 1 },
      { kind: "count", selector: MASK_SHAPES, atLeast: masksBefore + 1 },
    );
    const added = (await shownObjects(this.page)).filter((id) => !before.includes(id));
    expect(added, `one new object for ${truthId}`).toHaveLength(1);
    const id = added[0] as string;
    this.ids.set(truthId, id);
    return id;
  }

  /** Select an object by clicking it; Esc first when one is selected (a click would make it
   * that one's supporter). */
  async select(id: string): Promise<void> {
    // A click picks a supporter only while a pick is armed (an arrow was clicked).
    if ((await this.page.locator("svg.is-picking").count()) > 0)
      await this.key("Escape", "Esc (end the pick)");
    await this.act(`click ${id}`, () => clickObject(this.page, id));
    await expect(this.page.getByTestId(`object-row-${id}`)).toHaveClass(/is-selected/);
  }

  object(truthId: string) {
    const object = (this.truth.objects ?? []).find((o) => o.id === truthId);
    if (!object) throw new Error(`no true object ${truthId}`);
    return object;
  }

  /** How well the saved mask of `id` overlaps the truth's (what the annotator sees). */
  async maskQuality(truthId: string, id: string): Promise<number> {
    const doc = await getScene(this.page.request, this.sceneId);
    const saved = (doc.scene.objects ?? []).find((o) => o.id === id);
    return maskIou(this.object(truthId).mask, saved?.mask, this.truth.image.width);
  }

  /**
   * Refine the selected object's mask (`id`) with one foreground stroke down the middle of the
   * true mask (row by row), then go back to `backKey`'s tool.
   */
  async refineMask(truthId: string, id: string, backKey: string): Promise<void> {
    const path = strokeThrough(this.object(truthId).mask, 8);
    if (path.length < 2) return;
    const mask = this.page.getByTestId(`mask-${id}`);
    const outline = await mask.getAttribute("d"); // the mask's pixels as a path
    await this.key("k", "K (refine)");
    const points = [];
    for (const p of path) points.push(await toScreen(this.page, p));
    const [first, ...rest] = points;
    if (!first) return;
    await this.timed(
      `stroke over ${truthId}`,
      { kind: "changed", selector: `[data-testid="mask-${id}"]`, name: "d", from: outline },
      async () => {
        await this.page.mouse.move(first.x, first.y);
        await this.page.mouse.down();
        for (const p of rest) await this.page.mouse.move(p.x, p.y, { steps: 2 });
        await this.page.mouse.up();
      },
    );
    await expect(this.page.getByTestId("object-edit-status")).not.toHaveAttribute(
      "data-state",
      "busy",
    );
    this.masksFixed += 1;
    await this.key(backKey, `${backKey} (back)`);
  }

  /**
   * Give each true object its true supporter and type, in the object list: click the row's
   * supporter menu, choose (and the same for the type when it is wrong); Shift+A then accepts
   * the arrows that were right as shown.
   */
  async fixSupports(): Promise<void> {
    const page = this.page;
    const asApp = (truthId: string) =>
      STRUCTURAL_KEYS[truthId] ? truthId : (this.ids.get(truthId) ?? truthId);
    const wanted = (this.truth.supports ?? [])
      .filter((s) => this.ids.has(s.child))
      .map((s) => ({ child: asApp(s.child), parent: asApp(s.parent), type: s.type }));
    let accepted = 0;
    let inMenu = false;
    for (const { child, parent, type } of wanted) {
      const arrow = `.arrow[data-child="${child}"]`;
      const shown = (await shownGraph(page))[child];
      if (shown?.parent === parent && shown.type === type) {
        accepted += 1;
        continue;
      }
      // The supporter from its menu (also when only its type is wrong: a suggestion's type
      // menu is off until the supporter is set), then the type from its menu.
      const menu = page.getByTestId(`supporter-select-${child}`);
      if ((await menu.inputValue({ timeout: 15_000 })) !== parent) {
        // A click opens the menu (counted); Playwright picks the option without the native
        // popup, which can hold the page's frames in headless Chromium.
        await this.act(`open ${child}'s supporter menu`, () => menu.focus({ timeout: 15_000 }));
        inMenu = true;
        await this.timed(
          `${child} on ${parent}`,
          {
            kind: "attr",
            selector: `${arrow}[data-suggested="false"]`,
            name: "data-parent",
            value: parent,
          },
          () => menu.selectOption(parent, { timeout: 15_000 }),
        );
      }
      if ((await shownGraph(page))[child]?.type !== type) {
        const typeMenu = page.getByTestId(`type-select-${child}`);
        await this.act(`open ${child}'s type menu`, () => typeMenu.focus({ timeout: 15_000 }));
        inMenu = true;
        await this.timed(
          `${child} ${type}`,
          { kind: "attr", selector: arrow, name: "data-type", value: type },
          () => typeMenu.selectOption(type, { timeout: 15_000 }),
        );
      }
    }
    if (accepted === 0) return;
    // A menu keeps its keys (Shift+A would pick an option starting with A): a click beside it
    // first gives the keys back to the page.
    if (inMenu)
      await this.act("click beside the menus", () =>
        page.getByRole("heading", { name: "Support relations" }).click(),
      );
    await this.key("Shift+A", "Shift+A (accept the rest)");
  }
}

/** A stroke down the middle of a mask: each `step`-th row's middle inside pixel. */
function strokeThrough(mask: Mask | null | undefined, step: number): [number, number][] {
  if (!mask) return [];
  const [w, h] = mask.size;
  const [ox, oy] = mask.origin;
  const rows: number[][] = Array.from({ length: h }, () => []);
  let at = 0;
  mask.rle.forEach((run, i) => {
    if (i % 2 === 1) for (let p = at; p < at + run; p++) rows[Math.floor(p / w)]?.push(p % w);
    at += run;
  });
  const points: [number, number][] = [];
  for (let y = 0; y < h; y += step) {
    const xs = rows[y] ?? [];
    if (xs.length === 0) continue;
    points.push([ox + (xs[Math.floor(xs.length / 2)] as number) + 0.5, oy + y + 0.5]);
  }
  return points;
}

/** Objects in the order drawn: smallest first, so a larger box's corner is rarely on one. */
const drawingOrder = (truth: Scene) =>
  [...(truth.objects ?? [])]
    .sort(
      (a, b) =>
        (a.bbox[2] - a.bbox[0]) * (a.bbox[3] - a.bbox[1]) -
        (b.bbox[2] - b.bbox[0]) * (b.bbox[3] - b.bbox[1]),
    )
    .map((o) => o.id);

async function finish(run: Annotator, name: string): Promise<Run> {
  const page = run.page;
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved", {
    timeout: 30_000,
  });
  // Not an action: closes the last menu's open list, which would hide the photo's table.
  await page.keyboard.press("Escape");
  await page.evaluate(() => window.scrollTo(0, 0)); // the menus scrolled the page down
  await page.mouse.move(5, 5);
  await page.screenshot({ path: screenshotPath(`object-annotator-${name}.png`) });
  const saved = await getScene(page.request, run.sceneId);
  return {
    name,
    actions: run.actions,
    log: run.log,
    times: run.times,
    masksFixed: run.masksFixed,
    score: scoreScene(run.truth, saved.scene),
  };
}

// Tall enough for the whole photo under the detector's bar (a press below the window is lost).
test.use({ viewport: { width: 1440, height: 1200 } });

/**
 * With HOLISCENE_TRACE_DIR set, record a Chromium performance trace of the run (JavaScript
 * samples, layout and paint, each redraw's span as a user timing) into `<dir>/<name>.json`;
 * returns the function that stops it.
 */
async function traceRun(page: Page, name: string): Promise<() => Promise<void>> {
  const dir = process.env.HOLISCENE_TRACE_DIR;
  const browser = page.context().browser();
  if (!dir || !browser) return async () => {};
  mkdirSync(dir, { recursive: true });
  await browser.startTracing(page, {
    path: path.join(dir, `${name}.json`),
    categories: [
      "devtools.timeline",
      "disabled-by-default-devtools.timeline",
      "disabled-by-default-v8.cpu_profiler",
      "v8.execute",
      "blink.user_timing",
      "toplevel",
    ],
  });
  return async () => {
    await browser.stopTracing();
  };
}

async function openPlainPhoto(page: Page, name: string) {
  const { scene, truth } = plainPhoto(SEED);
  const doc = await importSynthetic(page.request, scene, name);
  expect(doc.scene.objects ?? []).toHaveLength(0);
  await watchInput(page);
  await page.goto("/");
  await setAuthor(page, "benchmark");
  await openScene(page, doc.scene_id);
  // The detector looks at an empty scene by itself: wait for its answer before starting.
  await expect(page.getByTestId("detector-status")).toContainText(/suggested in|No objects found/, {
    timeout: 90_000,
  });
  return { sceneId: doc.scene_id, truth };
}

test("run 1: a plain photo annotated without suggestions", async ({ page }, testInfo) => {
  test.setTimeout(10 * 60_000);
  const { sceneId, truth } = await openPlainPhoto(page, `synth-${SEED} (annotated by hand)`);
  const stopTrace = await traceRun(page, "by-hand");
  const run = new Annotator(page, sceneId, truth, "by-hand");
  if (await page.getByTestId("reject-all-suggestions").isVisible())
    await run.act("Reject all suggestions", () =>
      page.getByTestId("reject-all-suggestions").click(),
    );
  await run.key("b", "B (box tool)");
  for (const truthId of drawingOrder(truth)) {
    const id = await run.addObject(truthId);
    if ((await run.maskQuality(truthId, id)) < POOR_MASK) await run.refineMask(truthId, id, "b");
  }
  await waitForModel(page);
  await run.fixSupports();
  await stopTrace();
  const row = await report(await finish(run, "by-hand"), testInfo);
  expectComplete(row, testInfo);
  expect(row.actions, "actions without suggestions").toBeLessThanOrEqual(ACTIONS_WITHOUT);
});

/**
 * Make the registry's NYU-40 head active (better on synthetic rooms: the default COCO model
 * finds nothing on this photo; of the shipped candidates only it was trained, so only it has
 * a validation figure); returns the one to make active again.
 */
async function useSyntheticDetector(request: APIRequestContext): Promise<string> {
  const listed = await request.get("/api/models?kind=detector");
  expect(listed.ok()).toBe(true);
  const models = (await listed.json()) as ModelInfo[];
  const active = models.find((m) => m.active);
  const other = models.find((m) => !m.active && m.validation_accuracy != null);
  if (!active || !other) throw new Error("the registry should offer the NYU-40 head");
  await promote(request, other.id);
  return active.id;
}

// The detector to make active again after run 2, pass or fail: left to the NYU-40 head, the
// later specs' scenes would get its suggestions instead of the default's.
let restoreDetector: string | null = null;

test.afterEach(async ({ request }) => {
  if (restoreDetector === null) return;
  await promote(request, restoreDetector);
  restoreDetector = null;
});

async function promote(request: APIRequestContext, id: string) {
  const response = await request.post(`/api/models/${id}/promote`, {
    data: { author: "benchmark", note: "object annotator benchmark" },
  });
  expect(response.ok(), await response.text()).toBe(true);
}

test("run 2: the same photo annotated from the detector's suggestions", async ({
  page,
}, testInfo) => {
  test.setTimeout(10 * 60_000);
  restoreDetector = await useSyntheticDetector(page.request);
  test.info().annotations.push({ type: "detector", description: "the registry's NYU-40 head" });
  const { sceneId, truth } = await openPlainPhoto(page, `synth-${SEED} (from suggestions)`);
  const stopTrace = await traceRun(page, "from-suggestions");
  const run = new Annotator(page, sceneId, truth, "from-suggestions");
  const suggested = await page.getByTestId("detector-suggestion").count();
  if (suggested > 0) {
    await run.timed(
      "Shift+Y (accept all)",
      { kind: "count", selector: ".masks [data-object]", atLeast: suggested },
      () => page.keyboard.press("Shift+Y"),
      { kind: "count", selector: MASK_SHAPES, atLeast: suggested },
    );
  }
  const doc = await getScene(page.request, sceneId);
  const accepted = doc.scene.objects ?? [];
  const match = matchObjects(truth.objects ?? [], accepted);
  for (const [t, s] of match) run.ids.set(t, s);
  const matched = new Set(match.values());
  // False objects go: click one, Delete.
  for (const object of accepted.filter((o) => !matched.has(o.id))) {
    await run.select(object.id);
    await run.timed(
      `Delete ${object.id}`,
      { kind: "gone", selector: `[data-testid="mask-${object.id}"]` },
      () => page.keyboard.press("Delete"),
    );
  }
  // Wrong classes: the class in the object list, then pick.
  for (const [truthId, id] of match) {
    const want = run.object(truthId).class;
    if (accepted.find((o) => o.id === id)?.class === want) continue;
    await run.act(`click ${id}'s class in the list`, () =>
      page.getByTestId(`object-class-${id}`).click(),
    );
    await run.pickClass(want, {
      kind: "text",
      selector: `[data-testid="object-row-${id}"] .object-class`,
      text: want.replaceAll("_", " "),
    });
  }
  // Masks of the accepted objects, then the objects the detector missed.
  for (const [truthId, id] of match) {
    if ((await run.maskQuality(truthId, id)) >= POOR_MASK) continue;
    await run.select(id);
    await run.refineMask(truthId, id, "v");
  }
  const missed = drawingOrder(truth).filter((t) => !run.ids.has(t));
  if (missed.length > 0) await run.key("b", "B (box tool)");
  for (const truthId of missed) {
    const id = await run.addObject(truthId);
    if ((await run.maskQuality(truthId, id)) < POOR_MASK) await run.refineMask(truthId, id, "b");
  }
  await waitForModel(page);
  await run.fixSupports();
  await stopTrace();
  const row = await report({ ...(await finish(run, "from-suggestions")), suggested }, testInfo);
  expectComplete(row, testInfo);
  // The detector's recall decides much of this count (issue 18's accuracy targets are not met
  // yet: it finds 5 of the 9 objects here); the workbench must still keep it within target.
  noteTarget(testInfo, `${row.run}: actions`, row.actions, ACTIONS_WITH);
  expect(row.actions, "actions with suggestions").toBeLessThanOrEqual(ACTIONS_WITH);
});

/** Report a figure against its target (a benchmark's speed or a model's reach, not a pass
 * condition: docs/benchmarks.md keeps the figures). */
function noteTarget(testInfo: TestInfo, what: string, value: number, target: number) {
  const met = value <= target;
  const text = `${what}: ${value} (target ${target}${met ? ", met" : ", NOT MET"})`;
  testInfo.annotations.push({ type: met ? "target met" : "target not met", description: text });
  console.log(text);
}

/** The run's row of figures: printed, merged into the figures file, attached. */
async function report(run: Run, testInfo: TestInfo) {
  const s = run.score as SceneScore;
  const dom = run.times.map((t) => t.dom);
  const redraw = run.times.map((t) => t.redraw ?? t.dom);
  const painted = run.times.map((t) => t.painted ?? t.frame);
  const server = run.times.flatMap((t) => (t.server === null ? [] : [t.server]));
  const answerDrawn = run.times.flatMap((t) => (t.answerDrawn === null ? [] : [t.answerDrawn]));
  const row = {
    run: run.name,
    seed: SEED,
    actions: run.actions,
    actionsTarget: run.name === "by-hand" ? ACTIONS_WITHOUT : ACTIONS_WITH,
    suggested: run.suggested ?? null,
    objects: s.objects,
    matched: s.matched,
    extra: s.extra,
    classesRight: s.classesRight,
    meanMaskIou: Number(s.meanMaskIou.toFixed(3)),
    masksGood: s.masksGood,
    masksFixed: run.masksFixed,
    supportersRight: s.supportersRight,
    typesRight: s.typesRight,
    edits: run.times.length,
    redrawMedianMs: Number(median(redraw).toFixed(1)),
    redrawMaxMs: Number(Math.max(...redraw).toFixed(1)),
    frameMedianMs: Number(median(painted).toFixed(1)),
    frameMaxMs: Number(Math.max(...painted).toFixed(1)),
    shownMedianMs: Number(median(dom).toFixed(1)),
    shownMaxMs: Number(Math.max(...dom).toFixed(1)),
    serverMedianMs: Number(median(server).toFixed(1)),
    answerDrawnCount: answerDrawn.length,
    answerDrawnMedianMs: Number(median(answerDrawn).toFixed(1)),
    answerDrawnMaxMs: Number(Math.max(...answerDrawn).toFixed(1)),
  };
  const text = [
    `object annotator benchmark, ${run.name} (synth-${SEED}, ${s.objects} objects, truth from gt.json):`,
    `  ${row.actions} actions (target ${row.actionsTarget})` +
      (row.suggested === null ? "" : `, ${row.suggested} boxes suggested`),
    `  ${row.matched}/${s.objects} objects matched (box IoU >= 0.5), ${row.extra} extra; ` +
      `${row.classesRight} classes right; mean mask IoU ${row.meanMaskIou} ` +
      `(${row.masksGood} >= 0.5, ${row.masksFixed} refined); ` +
      `${row.supportersRight} supporters right, ${row.typesRight} types right`,
    `  ${row.edits} edits: redraw (answer or input to the page showing it) median ` +
      `${row.redrawMedianMs} ms, max ${row.redrawMaxMs} ms (target ${TARGET_MS} ms); ` +
      `to the next frame median ${row.frameMedianMs} ms, max ${row.frameMaxMs} ms; ` +
      `input to shown median ${row.shownMedianMs} ms, max ${row.shownMaxMs} ms ` +
      `(server answer median ${row.serverMedianMs} ms)`,
    `  ${row.answerDrawnCount} new-object edits shown by their box at once: their masks drawn ` +
      `from the server's answer in median ${row.answerDrawnMedianMs} ms, max ${row.answerDrawnMaxMs} ms`,
    `  actions: ${run.log.join(" | ")}`,
  ].join("\n");
  console.log(text);
  mkdirSync(FIGURES, { recursive: true });
  const file = path.join(FIGURES, "figures.json");
  const all = existsSync(file)
    ? (JSON.parse(readFileSync(file, "utf8")) as Record<string, unknown>)
    : {};
  all[run.name] = { ...row, log: run.log, times: run.times, rows: s.rows };
  writeFileSync(file, JSON.stringify(all, null, 1));
  await testInfo.attach(`object-annotator-${run.name}.json`, {
    body: JSON.stringify(all[run.name], null, 1),
    contentType: "application/json",
  });
  return row;
}

/** The scene is complete and right; the redraw time is reported against its target. */
function expectComplete(row: Awaited<ReturnType<typeof report>>, testInfo: TestInfo) {
  expect(row.matched, `${row.run}: every true object matched`).toBe(row.objects);
  expect(row.extra, `${row.run}: no false objects left`).toBe(0);
  expect(row.classesRight, `${row.run}: classes`).toBe(row.objects);
  expect(row.supportersRight, `${row.run}: supporters`).toBe(row.objects);
  // Timing depends on the machine's load: reported, not asserted.
  noteTarget(testInfo, `${row.run}: median edit-to-redraw ms`, row.redrawMedianMs, TARGET_MS);
  noteTarget(testInfo, `${row.run}: slowest edit-to-redraw ms`, row.redrawMaxMs, TARGET_MS);
  noteTarget(testInfo, `${row.run}: slowest answer-to-mask ms`, row.answerDrawnMaxMs, TARGET_MS);
}
