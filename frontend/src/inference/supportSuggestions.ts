// The Relation Network's answer beside each object of the support editor, on request: a
// "Model suggestions" button scores the scene in this browser (supportModel.ts) and shows each
// object's most probable supporter and type with its probability (the next answers in the
// tooltip). The model and onnxruntime-web load only when asked, then stay for the page.
import { api } from "../api/client";
import { el } from "../dom";
import type { SceneSession } from "../state/sceneSession";
import type { PixelImage } from "./preprocess";
import { type ObjectSupportScores, type SupportSuggestion, scoreSupports } from "./supportModel";

/**
 * The scene's photo as stored pixels (RGBA), without EXIF rotation or colour management, as
 * the backend decodes it (PIL).
 */
export async function photoPixels(url: string, signal?: AbortSignal): Promise<PixelImage> {
  const response = await fetch(url, { signal });
  if (!response.ok) throw new Error(`could not fetch the photo: ${response.status}`);
  const bitmap = await createImageBitmap(await response.blob(), {
    imageOrientation: "none",
    colorSpaceConversion: "none",
    premultiplyAlpha: "none",
  });
  const canvas = document.createElement("canvas");
  canvas.width = bitmap.width;
  canvas.height = bitmap.height;
  const context = canvas.getContext("2d", { willReadFrequently: true });
  if (!context) throw new Error("no 2D canvas to read the photo");
  context.drawImage(bitmap, 0, 0);
  bitmap.close();
  return context.getImageData(0, 0, canvas.width, canvas.height);
}

const percent = (p: number) => `${Math.round(p * 100)}%`;
const answer = (s: SupportSuggestion) => `${s.supporter} · ${s.type} ${percent(s.probability)}`;

/**
 * The button and status line (appended to `controls`) and the badges in `table`'s object rows
 * (`tr[data-object]`). Returns the function that removes them.
 */
export function mountSupportSuggestions(
  controls: HTMLElement,
  table: HTMLElement,
  session: SceneSession,
): () => void {
  const abort = new AbortController();
  const status = el("span", { className: "suggestion-status", testid: "suggestion-status" });
  const button = el("button", {
    text: "Model suggestions",
    testid: "suggest-supports",
    attrs: { type: "button", title: "Score every object's supporter with the support model" },
  });
  controls.append(el("div", { className: "suggestions" }, button, status));

  let scores: ObjectSupportScores[] | null = null;
  let photo: Promise<PixelImage> | null = null;
  let wanted = false;
  let run = 0;

  const render = () => {
    const shown = table.querySelectorAll(".badge--suggestion");
    if (shown.length === (scores?.length ?? 0) && [...shown].every((b) => b.isConnected)) return;
    for (const badge of shown) badge.remove();
    for (const s of scores ?? []) {
      const best = s.ranked[0];
      const cell = table.querySelector(`tr[data-object="${CSS.escape(s.id)}"] th`);
      if (!best || !cell) continue;
      cell.append(
        el("span", {
          className: "badge badge--suggestion",
          testid: `support-suggestion-${s.id}`,
          text: `model: ${answer(best)}`,
          attrs: { title: s.ranked.slice(0, 3).map(answer).join("\n") },
        }),
      );
    }
  };

  const score = async () => {
    const mine = ++run;
    button.disabled = true;
    status.textContent = "Scoring with the support model…";
    try {
      photo ??= photoPixels(api.imageUrl(session.sceneId), abort.signal);
      const start = performance.now();
      const result = await scoreSupports(session.doc.scene, await photo);
      if (mine !== run || abort.signal.aborted) return;
      scores = result;
      status.textContent = `${result.length} objects scored in ${Math.round(performance.now() - start)} ms`;
      render();
    } catch (error) {
      if (abort.signal.aborted) return;
      photo = null;
      status.textContent = `No suggestions: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      if (mine === run) button.disabled = false;
    }
  };

  button.addEventListener("click", () => {
    wanted = true;
    void score();
  });
  const unsubscribe = session.subscribe((change) => {
    // A new revision may move masks or objects: score again; otherwise rows may have been
    // rebuilt, so put the badges back.
    if (change === "document" && wanted) {
      scores = null;
      render();
      void score();
    } else {
      render();
    }
  });
  return () => {
    abort.abort();
    unsubscribe();
  };
}
