// The workflow spec's own server: accounts exist there from the start (an admin made with
// `holiscene users add` before `holiscene serve`), so login is required, while the other
// specs' server stays in local single-user mode.
import { readFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult, SceneSummary } from "@holiscene/schema";
import { type APIRequestContext, expect, type Page } from "@playwright/test";
import { waitForJob } from "./api";

// The port after the local-mode server's (HOLISCENE_E2E_PORT, default 8765).
export const WORKFLOW_PORT = Number(process.env.HOLISCENE_E2E_PORT ?? 8765) + 1;
export const WORKFLOW_URL = `http://127.0.0.1:${WORKFLOW_PORT}`;
export const ADMIN = { name: "e2e-admin", password: "tidal-quartz-Passw0rd-17" };

/** Log in through the API; the context then sends the session as a bearer token. */
export async function apiAs(
  newContext: (options: {
    baseURL: string;
    extraHTTPHeaders?: Record<string, string>;
  }) => Promise<APIRequestContext>,
  user: { name: string; password: string },
): Promise<APIRequestContext> {
  const anonymous = await newContext({ baseURL: WORKFLOW_URL });
  const response = await anonymous.post("/api/auth/login", {
    data: { name: user.name, password: user.password, token: true },
  });
  expect(response.status(), await response.text()).toBe(200);
  const { token } = (await response.json()) as { token: string };
  await anonymous.dispose();
  return newContext({
    baseURL: WORKFLOW_URL,
    extraHTTPHeaders: { Authorization: `Bearer ${token}` },
  });
}

/** Import an input folder (photo, cam_K.txt, detections.json) and wait for its pipeline. */
export async function importFolder(
  request: APIRequestContext,
  dir: string,
  photo: string,
  name: string,
): Promise<string> {
  const part = (file: string, mimeType: string) => ({
    name: file,
    mimeType,
    buffer: readFileSync(path.join(dir, file)),
  });
  const response = await request.post("/api/scenes", {
    multipart: {
      image: part(photo, photo.endsWith(".png") ? "image/png" : "image/jpeg"),
      cam_k: part("cam_K.txt", "text/plain"),
      detections: part("detections.json", "application/json"),
      name,
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (imported.job) {
    const job = await waitForJob(request, imported.job.id);
    expect(job.status, job.error ?? "").toBe("succeeded");
  }
  return imported.scene.id;
}

export { synthesizeFolder as synthesize } from "./synthetic";

export async function listScenes(request: APIRequestContext): Promise<SceneSummary[]> {
  const response = await request.get("/api/scenes");
  expect(response.ok()).toBe(true);
  return (await response.json()) as SceneSummary[];
}

export async function logIn(page: Page, name: string, password: string): Promise<void> {
  await expect(page.getByTestId("login-form")).toBeVisible();
  await page.getByTestId("login-name").fill(name);
  await page.getByTestId("login-password").fill(password);
  await page.getByTestId("login-submit").click();
  await expect(page.getByTestId("current-user")).toContainText(name);
}

export async function logOut(page: Page): Promise<void> {
  await page.getByTestId("logout").click();
  await expect(page.getByTestId("login-form")).toBeVisible();
  await expect(page.getByTestId("current-user")).toHaveCount(0);
}
