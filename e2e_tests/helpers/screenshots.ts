// Where the specs leave the screenshots a person looks at after a run (the folder is
// git-ignored and made on first use).
import { mkdirSync } from "node:fs";
import path from "node:path";

const SCREENSHOTS = path.resolve(import.meta.dirname, "../screenshots");

/** The file a screenshot called `name` is written to. */
export function screenshotPath(name: string): string {
  mkdirSync(SCREENSHOTS, { recursive: true });
  return path.join(SCREENSHOTS, name);
}
