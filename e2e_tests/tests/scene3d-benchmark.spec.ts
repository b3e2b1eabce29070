// Benchmark: frames per second of the page's 3D view while orbiting a scene of 50 objects
// (their meshes, 50 support arrows, the room, the photo's frustum) in headless Chromium on
// SwiftShader (software WebGL). Target: at least 30 frames/s.
//
// The scene is a synthetic room (seed 10, 24 objects) with 26 more boxes, imported with its
// detections so the pipeline places all 50. The orbit turns the view a little on every
// animation frame for ORBIT_MS through the same path as a drag (OrbitControls.update, whose
// change event asks for a frame); frames/s counts the frames the view rendered. A mouse drag
// is measured too, but Playwright waits for each move to be handled and drawn before sending
// the next, so it reports latency per move rather than the frame rate a user sees.
//
// Two browser set-ups: the Playwright config's flags (the page composited by SwiftShader as
// well), and --disable-gpu-compositing (the page composited by the CPU, WebGL still
// SwiftShader; what Chromium does by itself on a machine without a GPU). On software WebGL
// the view draws at half resolution while it moves (sharp again 200 ms after it stops): the
// figure is for those frames. Each set-up orbits three times (min, median and max frames/s)
// and reports the CPU time all the browser's processes spent per frame, which depends less
// on the machine's load than frames/s does (and is not capped at the display's 60 frames/s).
// A bare WebGL canvas of the same size that only clears each frame gives the ceiling the
// browser allows on this machine at this moment. The figures go with the load average: the
// development machines are shared.
//
// A second figure: how long a crowded room with depth (its objects' meshes completed from the
// depth, some 10^5 triangles) takes to parse and bake once its scene.glb has arrived, which
// holds the page's main thread while the scene opens.
//
// Without Playwright's trace recording: the config records a trace of every test (kept on
// failure), and a trace screencasts every page the test opens, the browsers launched here
// included. Encoding each frame of the 1440x1000 page cost more than drawing it: with the
// recorder the view made 28-37 frames/s (mouse drag 6-9), without it 58-60 (drag 40-47) at
// the same load, so the benchmark measured the recorder, not the page.
import { readdirSync, readFileSync } from "node:fs";
import { loadavg } from "node:os";
import path from "node:path";
import { type Browser, chromium, expect, type Page, test } from "@playwright/test";
import { fillUploadWithDepth, submitUploadAndWait } from "../helpers/photo";
import { nextFrames, openScene, scene3d, seedFolder, synthesize } from "../helpers/scene3d";
import { synthesizeFolder } from "../helpers/synthetic";

const OBJECTS = 50;
const CROWDED_DEPTH_SEED = 15; // 30 objects, with depth
const ORBIT_MS = 3000;
const ORBITS = 3;
const TARGET_FPS = 30;
const CLASSES = ["box", "books", "pillow", "picture", "lamp", "bag", "clothes", "towel"];
const SETUPS = [
  { name: "config flags", extra: [] as string[] },
  { name: "software compositing", extra: ["--disable-gpu-compositing"] },
];

test.use({ trace: "off" });

/** The synthetic room's boxes plus a grid of small ones, OBJECTS in all. */
function detections(folder: string): { bbox: number[]; class: string }[] {
  const given = JSON.parse(readFileSync(path.join(folder, "detections.json"), "utf8")) as {
    bbox: number[];
    class: string;
  }[];
  const boxes = [...given];
  for (let i = 0; boxes.length < OBJECTS; i++) {
    const x = 20 + (i % 7) * 88;
    const y = 40 + Math.floor(i / 7) * 105;
    boxes.push({ bbox: [x, y, x + 60, y + 70], class: CLASSES[i % CLASSES.length] as string });
  }
  return boxes;
}

/** Frames/s of a bare WebGL2 canvas of this size that clears every animation frame. */
async function ceilingFps(page: Page, width: number, height: number): Promise<number> {
  await page.setContent(`<canvas id="c" width="${width}" height="${height}"></canvas>`);
  return page.evaluate(async (ms) => {
    const canvas = document.getElementById("c") as HTMLCanvasElement;
    const gl = canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: false });
    if (!gl) throw new Error("no WebGL2");
    let frames = 0;
    const start = performance.now();
    await new Promise<void>((done) => {
      const tick = () => {
        gl.clearColor((frames % 10) / 10, 0.5, 0.5, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        frames += 1;
        if (performance.now() - start < ms) requestAnimationFrame(tick);
        else done();
      };
      requestAnimationFrame(tick);
    });
    return frames / ((performance.now() - start) / 1000);
  }, ORBIT_MS);
}

/** CPU seconds used so far by the browsers this worker launched (Linux /proc), or null. */
function browserCpuSeconds(): number | null {
  const stat = (pid: string) => {
    const text = readFileSync(`/proc/${pid}/stat`, "utf8");
    const fields = text.slice(text.lastIndexOf(")") + 2).split(" ");
    return { parent: Number(fields[1]), seconds: (Number(fields[11]) + Number(fields[12])) / 100 };
  };
  let pids: string[];
  try {
    pids = readdirSync("/proc").filter((name) => /^\d+$/.test(name));
  } catch {
    return null;
  }
  const processes = new Map<number, { parent: number; seconds: number }>();
  for (const pid of pids) {
    try {
      processes.set(Number(pid), stat(pid));
    } catch {} // ended meanwhile
  }
  const ours = (pid: number) => {
    for (let at = processes.get(pid); at; at = processes.get(at.parent)) {
      if (at.parent === process.pid) return true;
    }
    return false;
  };
  let total = 0;
  for (const [pid, { seconds }] of processes) if (ours(pid)) total += seconds;
  return total;
}

interface Orbit {
  fps: number;
  renderMs: number;
  size: string;
  /** CPU milliseconds per frame, all the browser's processes (null without /proc). */
  cpuMs: number | null;
}

/** Frames/s of the 3D view turned a little on every animation frame for ORBIT_MS. */
async function orbitFps(page: Page): Promise<Orbit> {
  const cpuBefore = browserCpuSeconds();
  const orbit = await page.getByTestId("scene3d-canvas").evaluate(async (canvas, ms) => {
    const probe = (
      canvas as unknown as {
        scene3dProbe: {
          frames: number;
          renderMs: number[];
          orbit(azimuth: number): void;
          renderInfo(): { width: number; height: number };
        };
      }
    ).scene3dProbe;
    const first = probe.frames;
    const start = performance.now();
    await new Promise<void>((done) => {
      const tick = () => {
        probe.orbit(0.02);
        if (performance.now() - start < ms) requestAnimationFrame(tick);
        else done();
      };
      requestAnimationFrame(tick);
    });
    const { width, height } = probe.renderInfo(); // the last frame drawn while moving
    const frames = probe.frames - first;
    const recent = probe.renderMs.slice(-Math.max(frames, 1));
    return {
      frames,
      fps: frames / ((performance.now() - start) / 1000),
      renderMs: recent.reduce((s, t) => s + t, 0) / recent.length,
      size: `${width}x${height}`,
    };
  }, ORBIT_MS);
  const cpuAfter = browserCpuSeconds();
  const { frames, ...rest } = orbit;
  const cpuMs =
    cpuBefore === null || cpuAfter === null ? null : ((cpuAfter - cpuBefore) * 1000) / frames;
  return { ...rest, cpuMs };
}

const median = (values: number[]) => [...values].sort((a, b) => a - b)[values.length >> 1] ?? 0;

/** Frames/s and mouse moves/s while dragging in circles over the canvas for ORBIT_MS. */
async function dragFps(page: Page): Promise<{ fps: number; moves: number }> {
  const canvas = page.getByTestId("scene3d-canvas");
  const box = await canvas.boundingBox();
  if (!box) throw new Error("the 3D canvas is not laid out");
  const cx = box.x + box.width / 2;
  const cy = box.y + box.height / 2;
  const radius = Math.min(box.width, box.height) * 0.3;
  await page.mouse.move(cx + radius, cy);
  await page.mouse.down();
  const before = await scene3d(page, (p) => ({ frames: p.frames, at: performance.now() }));
  let moves = 0;
  const start = Date.now();
  while (Date.now() - start < ORBIT_MS) {
    const angle = (moves * Math.PI) / 30;
    await page.mouse.move(cx + radius * Math.cos(angle), cy + radius * Math.sin(angle) * 0.5);
    moves += 1;
  }
  const after = await scene3d(page, (p) => ({ frames: p.frames, at: performance.now() }));
  await page.mouse.up();
  const seconds = (after.at - before.at) / 1000;
  return { fps: (after.frames - before.frames) / seconds, moves: moves / seconds };
}

test("3D view: frames per second while orbiting 50 objects", async ({ request, baseURL }) => {
  test.setTimeout(900_000);
  const folder = synthesize(10);
  const doc = await seedFolder(request, folder, "benchmark 50 objects", detections(folder));
  const objects = doc.scene.objects ?? [];
  expect(objects.length).toBe(OBJECTS);
  expect(objects.filter((o) => o.box_3d).length).toBeGreaterThanOrEqual(OBJECTS - 2);
  const args = test.info().project.use.launchOptions?.args ?? [];
  const results: Record<string, number> = {};

  for (const setup of SETUPS) {
    let browser: Browser | null = null;
    try {
      browser = await chromium.launch({
        executablePath: "/usr/bin/chromium",
        args: [...args, ...setup.extra],
      });
      const page = await browser.newPage({ baseURL, viewport: { width: 1440, height: 1000 } });
      await openScene(page, doc.scene_id);
      await expect
        .poll(() => scene3d(page, (p) => p.photoOnFrustum()), { timeout: 60_000 })
        .toBe(true);
      const arrows = await scene3d(page, (p) => p.arrows().length);
      expect(arrows).toBeGreaterThanOrEqual(OBJECTS - 2);
      const canvas = page.getByTestId("scene3d-canvas");
      await canvas.scrollIntoViewIfNeeded();
      await nextFrames(page);
      // The view's full size (it moves at half resolution for a while after it is set up).
      const fullSize = () =>
        canvas.evaluate((c) => {
          const dpr = Math.min(window.devicePixelRatio, 2);
          const full = Math.floor(c.clientWidth * dpr);
          return (c as HTMLCanvasElement).width === full
            ? [full, (c as HTMLCanvasElement).height]
            : null;
        });
      await expect.poll(fullSize, { timeout: 10_000 }).not.toBeNull();
      const [width, height] = (await fullSize()) ?? [0, 0];
      await orbitFps(page); // shaders compiled, caches warm
      const orbits: Orbit[] = [];
      for (let i = 0; i < ORBITS; i++) orbits.push(await orbitFps(page));
      const rates = orbits.map((o) => o.fps);
      const orbit = orbits.find((o) => o.fps === median(rates)) ?? (orbits[0] as Orbit);
      const cpu = orbits.flatMap((o) => (o.cpuMs === null ? [] : [o.cpuMs]));
      const drag = await dragFps(page);
      const info = await scene3d(page, (p) => p.renderInfo());
      if (setup.extra.length > 0) {
        await canvas.screenshot({
          path: path.resolve(import.meta.dirname, "../screenshots/scene3d-benchmark.png"),
        });
      }
      const ceiling = await ceilingFps(page, width ?? 0, height ?? 0);
      const load = loadavg()
        .map((l) => l.toFixed(2))
        .join(", ");
      const spread = [Math.min(...rates), median(rates), Math.max(...rates)];
      console.log(
        `3D view (${setup.name}), ${OBJECTS} objects, ${arrows} arrows, ${info.calls} draw calls, ` +
          `${info.triangles} triangles, canvas ${width}x${height} (${orbit.size} ` +
          `while moving): orbiting ${spread.map((f) => f.toFixed(1)).join(" / ")} frames/s ` +
          `(min / median / max of ${ORBITS}; ` +
          (cpu.length > 0 ? `${median(cpu).toFixed(1)} ms CPU per frame, all processes; ` : "") +
          `render call ${orbit.renderMs.toFixed(2)} ms); mouse drag ${drag.fps.toFixed(1)} ` +
          `frames/s at ${drag.moves.toFixed(1)} moves/s; bare WebGL canvas ${ceiling.toFixed(1)} ` +
          `frames/s; load average ${load}`,
      );
      results[setup.name] = median(rates);
    } finally {
      await browser?.close();
    }
  }
  // The figure is reported against the target, not gated: software WebGL's frame rate here
  // follows the machine's load (docs/benchmarks.md, the 3D view), so a gate would test the
  // machine, not the page. That frames were drawn at all is checked.
  const best = Math.max(...Object.values(results));
  console.log(
    `3D view, best setup: ${best.toFixed(1)} frames/s (${best >= TARGET_FPS ? "within" : "under"} the ${TARGET_FPS} frames/s target)`,
  );
  for (const fps of Object.values(results)) expect(fps).toBeGreaterThan(0);
});

test("3D view: a crowded room with depth, its scene.glb parsed and baked", async ({ page }) => {
  test.setTimeout(300_000);
  const dir = synthesizeFolder(CROWDED_DEPTH_SEED);
  await page.goto("/#/");
  await fillUploadWithDepth(page, dir, "crowded room with depth");
  await submitUploadAndWait(page);
  await page.getByTestId("upload-open").click();
  await expect(page.getByTestId("scene3d-canvas")).toHaveAttribute("data-status", "ready", {
    timeout: 120_000,
  });
  const load = await scene3d(page, (p) => p.glbLoad());
  if (!load) throw new Error("the 3D view shows no scene.glb");
  expect(load.triangles).toBeGreaterThan(10_000);
  const objects = await page.locator("[data-testid^='object-row-']").count();
  const average = loadavg()
    .map((l) => l.toFixed(2))
    .join(", ");
  console.log(
    `3D view, a room with depth (seed ${CROWDED_DEPTH_SEED}, ${objects} objects): scene.glb of ` +
      `${Math.round(load.triangles)} triangles parsed and baked in ${load.ms.toFixed(0)} ms; ` +
      `load average ${average}`,
  );
});
