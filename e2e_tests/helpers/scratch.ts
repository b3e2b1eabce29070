// Scratch folders for a test (synthetic scenes, edited copies of them): inside the run's data
// directory, which the global teardown removes, so test runs leave nothing behind in /tmp.
import { mkdirSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

export function scratchDir(prefix: string): string {
  const run = process.env.HOLISCENE_E2E_DATA_DIR;
  const root = run ? path.join(run, "scratch") : tmpdir();
  mkdirSync(root, { recursive: true });
  return mkdtempSync(path.join(root, prefix));
}
