// Remove the run's data directory (set HOLISCENE_E2E_KEEP_DATA=1 to keep it for debugging).
import { rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";

export default function globalTeardown(): void {
  const dir = process.env.HOLISCENE_E2E_DATA_DIR;
  if (!dir || process.env.HOLISCENE_E2E_KEEP_DATA) return;
  if (path.dirname(dir) !== tmpdir() || !path.basename(dir).startsWith("holiscene-e2e-")) return;
  rmSync(dir, { recursive: true, force: true });
}
