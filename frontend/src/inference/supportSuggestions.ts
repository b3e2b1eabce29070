// The Relation Network in the scene page. When the scene opens (unless live suggestions are
// switched off) the photo and masks are scored once in this browser (supportModel.ts); from
// then on every edit decodes the tree again with the corrections pinned (suggester.ts), so
// the remaining guesses follow each correction at once, without the server. Each object's row
// also shows the model's most probable supporter and type (the next answers in the tooltip).

import type { SceneObject } from "@holiscene/schema";
import { deferred } from "../afterPaint";
import { api } from "../api/client";
import { button, el } from "../dom";
import { plural, type SceneSession } from "../state/sceneSession";
import { doubtedLabels } from "./labelDoubts";
import type { PixelImage } from "./preprocess";
import { makeSuggester } from "./suggester";
import { showSuggestionBadges } from "./suggestionBadges";
import { type SceneScores, scoreScene } from "./supportModel";

const SETTING = "holiscene.liveSuggestions";

/** Live suggestions are on unless the user switched them off (remembered in this browser). */
export function liveSuggestionsEnabled(): boolean {
  try {
    return localStorage.getItem(SETTING) !== "off";
  } catch {
    return true;
  }
}

function rememberEnabled(on: boolean): void {
  try {
    localStorage.setItem(SETTING, on ? "on" : "off");
  } catch {
    // not remembered: this page only
  }
}

/**
 * The scene's photo as stored pixels (RGBA), without colour management, as the backend
 * decodes it (PIL). A stored photo carries no EXIF turn: the backend stores it upright.
 */
export async function photoPixels(url: string, signal?: AbortSignal): Promise<PixelImage> {
  // The photo's bytes, decoded here: a plain fetch (request() is for JSON messages).
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

/** What the model's inputs depend on: scoring again is needed only when this changes. */
const inputsKey = (objects: readonly SceneObject[]) =>
  JSON.stringify(objects.map((o) => [o.id, o.class, o.bbox, o.mask]));

/**
 * The controls and status line (appended to `controls`) and the badges in `table`'s object
 * rows (`tr[data-object]`). Returns the function that removes them.
 */
export function mountSupportSuggestions(
  controls: HTMLElement,
  table: HTMLElement,
  session: SceneSession,
): () => void {
  const abort = new AbortController();
  const status = el("span", { className: "suggestion-status", testid: "suggestion-status" });
  const suggestButton = button("Model suggestions", {
    testid: "suggest-supports",
    title: "Score every object's supporter with the support model",
  });
  const live = el("input", {
    testid: "live-suggestions",
    attrs: { type: "checkbox", checked: liveSuggestionsEnabled() },
  });
  controls.append(
    el(
      "div",
      { className: "suggestions" },
      suggestButton,
      el(
        "label",
        {
          className: "toggle",
          attrs: { title: "Score the scene when it opens and follow each correction" },
        },
        live,
        "Live",
      ),
      status,
    ),
  );

  let scores: SceneScores | null = null;
  /** The objects the scores (or the run under way) are for. */
  let scoredFor = "";
  let photo: Promise<PixelImage> | null = null;
  let run = 0;

  const render = () => showSuggestionBadges(table, scores, doubtedLabels(session.shown(), scores));
  // Doubts only from scores for the objects as they are now (not while a new scoring is due).
  session.setDoubter(() =>
    scores !== null && !due && inputsKey(session.objects) === scoredFor
      ? new Set(doubtedLabels(session.shown(), scores).keys())
      : new Set(),
  );

  const describe = (ms: number) => {
    const count = scores?.ids.length ?? 0;
    const suggested = session.suggestions().size;
    const doubted = doubtedLabels(session.shown(), scores).size;
    // Parts joined by "; ": a wrapped line ends on the mark and starts with a word (a "·"
    // started or ended a line, where it read as a stray dot).
    status.textContent = [
      // Which model: after an admin switches models, people can tell whose scores these are.
      `${plural(count, "object")} scored in ${Math.round(ms)} ms` +
        (scores?.modelVersion === undefined
          ? ""
          : ` by the Relation Network v${scores.modelVersion}`),
      // Read only (a reviewer), nothing is suggested: saying "no changes" would mislead.
      // Live suggestions replace guesses only: "no changes" read as the model agreeing with
      // every label, people's too.
      live.checked && session.editable
        ? `live: ${suggested === 0 ? "no guess to change" : `${plural(suggested, "guess")} to change`}`
        : "",
      doubted > 0
        ? `the model disagrees with ${plural(doubted, "label")} set by a person (orange)`
        : "",
    ]
      .filter((part) => part !== "")
      .join("; ");
    status.classList.toggle("has-doubts", doubted > 0);
  };
  let scoredMs = 0;
  /** The objects changed since the scores shown: a new scoring is due (the status says so). */
  let due = false;

  const score = async () => {
    const mine = ++run;
    suggestButton.disabled = true;
    status.textContent = "Scoring with the support model…";
    try {
      photo ??= photoPixels(api.imageUrl(session.sceneId), abort.signal);
      const start = performance.now();
      scoredFor = inputsKey(session.objects);
      const result = await scoreScene(session.doc.scene, await photo);
      if (mine !== run || abort.signal.aborted) return;
      scores = result;
      due = false;
      scoredMs = performance.now() - start;
      session.setSuggester(live.checked ? makeSuggester(result) : null);
      render();
      describe(scoredMs);
    } catch (error) {
      if (abort.signal.aborted || mine !== run) return;
      photo = null;
      status.textContent = `No suggestions: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      if (mine === run) suggestButton.disabled = false;
    }
  };

  suggestButton.addEventListener("click", () => void score());
  live.addEventListener("change", () => {
    rememberEnabled(live.checked);
    if (!live.checked) session.setSuggester(null);
    else if (scores) session.setSuggester(makeSuggester(scores));
    else void score();
    if (scores && !due) describe(scoredMs);
  });
  // After the new revision is drawn: scoring (and dropping the old scores, which redraws the
  // arrows) would hold the photo's redraw back.
  const scoreLater = deferred(() => {
    if (inputsKey(session.objects) === scoredFor) {
      due = false;
      if (scores) describe(scoredMs); // back to the objects scored (a refused action)
      return;
    }
    scores = null;
    session.setSuggester(null);
    render();
    void score();
  });
  const unsubscribe = session.subscribe((change) => {
    // A revision that added, removed or changed objects (an object edit, a placement) needs
    // scoring again, also while a run for the old objects is under way (its answer is
    // dropped); support edits only need decoding again, which the session does itself. Rows
    // may have been rebuilt: put badges back.
    const wanted = scores !== null || live.checked;
    if (change === "document" && wanted && inputsKey(session.objects) !== scoredFor) {
      render();
      // The scores shown are for the objects before: say so now, not after the next scoring
      // begins (the status must never claim scores for objects they were not made for).
      due = true;
      status.textContent = "Scoring with the support model…";
      scoreLater();
    } else {
      render();
      if (scores && !due && (change === "edits" || change === "document")) describe(scoredMs);
    }
  });
  if (live.checked) {
    // After the page has drawn: loading the runtime and the model takes a second or two.
    const start = setTimeout(() => void score(), 50);
    abort.signal.addEventListener("abort", () => clearTimeout(start));
  }
  return () => {
    scoreLater.cancel();
    abort.abort();
    unsubscribe();
    session.setSuggester(null);
    session.setDoubter(null);
  };
}
