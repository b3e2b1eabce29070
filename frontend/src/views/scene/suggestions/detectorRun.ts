// One run of the object detector on the scene's photo, in this browser, and what to say about
// what it found.
import { api } from "../../../api/client";
import { ApiError } from "../../../api/errors";
import { activeDetector, detectorModel, suggesterDetector } from "../../../inference/detector";
import { type DetectedBox, isFlatPhoto, SCORE_THRESHOLD } from "../../../inference/detectorTensor";
import type { PixelImage } from "../../../inference/preprocess";
import { photoPixels } from "../../../inference/supportSuggestions";
import { plural } from "../../../state/sceneSession";
import { HINT_SCORE } from "../classHints";

const MB = (bytes: number) => `${(bytes / 1e6).toFixed(1)} MB`;

export interface DetectorRun {
  /** Every box down to HINT_SCORE: the offers (at the model's score threshold, SCORE_THRESHOLD),
   * the guesses when there is no suggester, and the class picker's hints. */
  seen: DetectedBox[];
  /** Loading the detector (about nothing once its session exists), milliseconds. */
  loadMs: number;
  /** Reading the photo and detecting, milliseconds. */
  runMs: number;
  /** The photo is one flat colour: the detector was not run (isFlatPhoto). */
  flat: boolean;
  /** Which detector ran (the registry's active one), as its metadata names it. */
  detector: string;
  /** The photo it ran on (the suggester runs on it next). */
  pixels: PixelImage;
}

/**
 * Load the active detector (`say` hears how far its download is) and run it on the photo;
 * `detecting` is told when loading is done.
 */
export async function runDetector(
  sceneId: string,
  say: (text: string) => void,
  detecting: () => void,
): Promise<DetectorRun> {
  const start = performance.now();
  let loading = true;
  const info = await activeDetector();
  const model = await detectorModel(info, (loaded, total) => {
    if (loading)
      say(`Loading the object detector… ${MB(loaded)} of ${MB(total ?? info.model_bytes)}`);
  });
  loading = false;
  const loaded = performance.now();
  detecting();
  const pixels = await photoPixels(api.imageUrl(sceneId));
  const flat = isFlatPhoto(pixels);
  // One decoding at the hints' score: its boxes above the threshold are exactly the offers
  // (the per-class suppression only ever drops a box for a better one).
  const seen = flat ? [] : (await model.detect(pixels, HINT_SCORE)).boxes;
  return {
    seen,
    loadMs: loaded - start,
    runMs: performance.now() - loaded,
    flat,
    detector: info.name,
    pixels,
  };
}

/** The guesses on the run's photo: the suggester's boxes at the contract's threshold, or null
 * when no suggester is installed (the detector's own fainter boxes are the guesses then). */
export async function runSuggester(run: DetectorRun): Promise<DetectedBox[] | null> {
  if (run.flat) return [];
  let info: Awaited<ReturnType<typeof suggesterDetector>>;
  try {
    info = await suggesterDetector();
  } catch (error) {
    if (error instanceof ApiError && error.status === 404) return null;
    throw error;
  }
  const model = await detectorModel(info);
  return (await model.detect(run.pixels, SCORE_THRESHOLD)).boxes;
}

/** A detector's name as the status line says it: up to its first comma or bracket ("COCO
 * PicoDet-S 416"); the whole name is on the models page. At 1280 px the line cut it at "COCO
 * Pico…". */
export const shortDetectorName = (name: string): string => name.split(/,| \(/)[0]?.trim() || name;

/** What the run found, for the status line: `found` boxes, `open` of them not labelled yet,
 * `rejected` left out as rejected before (the guesses have their own button in the bar). */
export function foundText(found: number, open: number, run: DetectorRun, rejected = 0): string {
  const seconds = (ms: number) => `${(ms / 1000).toFixed(1)} s`;
  // Which detector: after an admin switches models, a reviewer can tell whose boxes these are.
  // (How long loading it took is the benchmark's business: the line was cut before its end.)
  const time = `in ${seconds(run.runMs)} by ${shortDetectorName(run.detector)}`;
  if (run.flat) return "The photo is one flat colour: there is nothing to detect in it.";
  if (found === 0) return `No objects found ${time}.`;
  // What matters first: the status line shows one line, cut at its end (the rest in its title).
  const left = rejected > 0 ? ` (${rejected} rejected before left out)` : "";
  if (open === 0) {
    // Boxes, not objects: two boxes of one object (a bed also found as a sofa) count twice.
    const settled = rejected > 0 ? "labelled or rejected already" : "labelled already";
    const all =
      found === 1
        ? `Nothing new: the box found is on an object ${settled}`
        : `Nothing new: the ${found} boxes found are on objects ${settled}`;
    return `${all}${left}, ${time}.`;
  }
  return `${plural(open, "object")} suggested${left} ${time}: click a box, then Accept or Reject.`;
}
