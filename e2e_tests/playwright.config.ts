// End-to-end tests: the built frontend served by a real `holiscene serve` on a fresh data
// directory (SQLite). `npm test` builds the frontend first; the backend serves frontend/dist.
import { mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { defineConfig } from "@playwright/test";

// HOLISCENE_E2E_PORT: another port, for runs beside another one on the same machine.
const PORT = Number(process.env.HOLISCENE_E2E_PORT ?? 8765);
const BASE_URL = `http://127.0.0.1:${PORT}`;

// The config is evaluated again in each worker; the environment keeps one directory per run.
process.env.HOLISCENE_E2E_DATA_DIR ??= mkdtempSync(path.join(tmpdir(), "holiscene-e2e-"));
const dataDir = process.env.HOLISCENE_E2E_DATA_DIR;
// Unset, so the server keeps its database (SQLite) inside the fresh data directory.
delete process.env.HOLISCENE_DATABASE_URL;

export default defineConfig({
  testDir: "./tests",
  outputDir: "./test-results",
  timeout: 180_000,
  expect: { timeout: 15_000 },
  fullyParallel: false,
  workers: 1,
  retries: 0,
  reporter: "list",
  globalTeardown: "./global-teardown.ts",
  use: {
    baseURL: BASE_URL,
    headless: true,
    viewport: { width: 1440, height: 1000 },
    trace: "retain-on-failure",
    screenshot: "only-on-failure",
    launchOptions: {
      executablePath: "/usr/bin/chromium",
      args: [
        "--no-sandbox",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--no-first-run",
        "--enable-unsafe-swiftshader",
        "--use-angle=swiftshader",
      ],
    },
  },
  webServer: {
    command: `../.venv/bin/holiscene serve --port ${PORT} --data-dir ${dataDir}`,
    url: `${BASE_URL}/api/health`,
    reuseExistingServer: false,
    timeout: 60_000,
    stdout: "pipe",
    stderr: "pipe",
  },
});
