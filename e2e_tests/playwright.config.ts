// End-to-end tests: the built frontend served by a real `holiscene serve` on a fresh data
// directory (SQLite). `npm test` builds the frontend first; the backend serves frontend/dist.
import { mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { defineConfig } from "@playwright/test";
import { ADMIN, WORKFLOW_PORT, WORKFLOW_URL } from "./helpers/workflow";

// HOLISCENE_E2E_PORT: another port, for runs beside another one on the same machine.
const PORT = Number(process.env.HOLISCENE_E2E_PORT ?? 8765);
const BASE_URL = `http://127.0.0.1:${PORT}`;

// The config is evaluated again in each worker; the environment keeps one directory per run.
process.env.HOLISCENE_E2E_DATA_DIR ??= mkdtempSync(path.join(tmpdir(), "holiscene-e2e-"));
const dataDir = process.env.HOLISCENE_E2E_DATA_DIR;
// Unset, so the server keeps its database (SQLite) inside the fresh data directory.
delete process.env.HOLISCENE_DATABASE_URL;
// The workflow spec's server has accounts (login required); the first server stays in local
// single-user mode for every other spec. Inside the run's directory, so teardown removes it.
const workflowDir = path.join(dataDir, "workflow-server");
const WORKFLOW_SPEC = /workflow-roles\.spec\.ts$/;

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
  projects: [
    { name: "local-mode", testIgnore: WORKFLOW_SPEC },
    { name: "accounts", testMatch: WORKFLOW_SPEC, use: { baseURL: WORKFLOW_URL } },
  ],
  webServer: [
    {
      command: `../.venv/bin/holiscene serve --port ${PORT} --data-dir ${dataDir}`,
      url: `${BASE_URL}/api/health`,
      reuseExistingServer: false,
      timeout: 60_000,
      stdout: "pipe",
      stderr: "pipe",
    },
    {
      // The admin comes from the CLI, as on a real server (no default credentials).
      command:
        `../.venv/bin/holiscene users add ${ADMIN.name} --role admin --data-dir ${workflowDir} && ` +
        `exec ../.venv/bin/holiscene serve --port ${WORKFLOW_PORT} --data-dir ${workflowDir}`,
      env: { HOLISCENE_PASSWORD: ADMIN.password },
      url: `${WORKFLOW_URL}/api/health`,
      reuseExistingServer: false,
      timeout: 60_000,
      stdout: "pipe",
      stderr: "pipe",
    },
  ],
});
