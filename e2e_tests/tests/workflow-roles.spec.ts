// User story: an admin creates an annotator and a reviewer; the annotator takes the next
// scene (the most uncertain first) on a real photo and on a synthetic room, corrects a
// supporter and submits both; the reviewer rejects one with a comment and accepts the other;
// the annotator sees the comment, fixes the scene and resubmits; the reviewer accepts; the
// dashboard shows the counts. A submitted scene is read only for its annotator (a banner says
// why; editing and its keys are off, the key list still opens)
// until the reviewer sends it back. Runs on its own server, where login is required.
import path from "node:path";
import type { SceneDocument, SceneWorkflow } from "@holiscene/schema";
import {
  type APIRequestContext,
  expect,
  type Page,
  type PlaywrightWorkerArgs,
  test,
} from "@playwright/test";
import { answeringYes } from "../helpers/dialogs";
import { clickObject } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";
import {
  ADMIN,
  apiAs,
  importFolder,
  listScenes,
  logIn,
  logOut,
  synthesize,
  WORKFLOW_URL,
} from "../helpers/workflow";

const REAL_PHOTO = path.resolve(import.meta.dirname, "../../../shared/data/real/im3d-3");
const ANNOTATOR = { name: "anna", password: "marble-otter-62-sky" };
const REVIEWER = { name: "rudi", password: "copper-fjord-35-lime" };

const shot = (page: Page, name: string) =>
  page.screenshot({ path: screenshotPath(`workflow-${name}.png`), fullPage: true });

async function workflowOf(request: APIRequestContext, sceneId: string): Promise<SceneWorkflow> {
  return (await (await request.get(`/api/scenes/${sceneId}/workflow`)).json()) as SceneWorkflow;
}

/** Change one object's supporter in the editor (not saved yet). */
async function correctASupporterUnsaved(page: Page, request: APIRequestContext, sceneId: string) {
  const doc = (await (await request.get(`/api/scenes/${sceneId}`)).json()) as SceneDocument;
  const supports = doc.scene.supports ?? [];
  const child = supports.find((s) => s.parent !== "floor" && s.source === "auto") ?? supports[0];
  if (!child) throw new Error(`scene ${sceneId} has no supports to correct`);
  const target = child.parent === "floor" ? "wall" : "floor";
  await page.getByTestId(`supporter-select-${child.child}`).selectOption(target);
  return { child: child.child, target };
}

/** Change one object's supporter in the editor and wait until it is saved. */
async function correctASupporter(page: Page, request: APIRequestContext, sceneId: string) {
  const { child, target } = await correctASupporterUnsaved(page, request, sceneId);
  await page.keyboard.press("Control+s"); // edits also save by themselves after a pause
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  await expect(page.getByTestId(`supporter-select-${child}`)).toHaveValue(target);
  return child;
}

/** Submit from the workflow bar, answering Yes to what it asks first (if anything). */
async function submitAnsweringYes(page: Page): Promise<void> {
  await answeringYes(page, async () => {
    await page.getByTestId("workflow-submit").click();
    await expect(page.getByTestId("workflow-state")).toHaveText("submitted");
  });
}

/**
 * The scene page is read only: the banner says why, the support editor and the layout editor
 * are off and so are their keys (F does nothing to the selected object, E starts no layout
 * editing, Ctrl+Z undoes nothing), while "?" still lists the keys (the editing ones greyed).
 */
async function expectReadOnly(page: Page, sceneId: string, title: string): Promise<void> {
  const banner = page.getByTestId("read-only-banner");
  await expect(banner).toBeVisible();
  await expect(page.getByTestId("read-only-reason")).toHaveText(title);
  await expect(banner).toHaveAttribute(
    "title",
    /^Editing \(supports, objects, room\) and its keys are off/,
  );
  const selects = page.locator("[data-testid^='supporter-select-']");
  for (const select of await selects.all()) await expect(select).toBeDisabled();
  await expect(page.getByTestId("layout-toggle")).toBeDisabled();
  // Nothing unsaved: Undo, Redo, Discard and Save are left out, not greyed.
  await expect(page.getByTestId("undo-button")).toBeHidden();
  await expect(page.getByTestId("save-button")).toBeHidden();
  await expect(page.getByTestId("save-status")).toBeVisible();
  await expect(page.getByTestId("run-pipeline")).toBeDisabled();
  // The line under the photo offers no key that would change anything.
  await expect(page.getByTestId("edge-info-hint")).toContainText(/read only/i);
  await expect(page.getByTestId("edge-info-hint")).not.toContainText("Shift+A");

  const before = (await (await page.request.get(`/api/scenes/${sceneId}`)).json()) as SceneDocument;
  const child = (before.scene.supports ?? []).find((s) => s.parent !== "floor")?.child;
  if (!child) throw new Error("no object to try the F key on");
  await clickObject(page, child); // read only, a click still selects
  await expect(page.getByTestId(`object-row-${child}`)).toHaveClass(/is-selected/);
  for (const key of ["f", "e", "Control+z"]) await page.keyboard.press(key);
  await expect(page.getByTestId("layout-bar")).toHaveAttribute("data-editing", "false");
  await expect(page.getByTestId(`supporter-select-${child}`)).not.toHaveValue("floor");
  await expect(page.getByTestId("pending-edits")).toBeHidden();

  await page.keyboard.press("?");
  const help = page.getByTestId("shortcut-help");
  await expect(help).toBeVisible();
  await expect(help.locator("[data-keys='F']")).toHaveAttribute("data-enabled", "false");
  await expect(help.locator("[data-keys='E']")).toHaveAttribute("data-enabled", "false");
  await expect(help.locator("[data-keys='?']")).toHaveAttribute("data-enabled", "true");
  await page.keyboard.press("Escape");
  await expect(help).toBeHidden();
  const after = (await (await page.request.get(`/api/scenes/${sceneId}`)).json()) as SceneDocument;
  expect(after.revision).toBe(before.revision);
}

/** Makes API request contexts (for apiAs). */
const requestContexts =
  (playwright: PlaywrightWorkerArgs["playwright"]) =>
  (options: { baseURL: string; extraHTTPHeaders?: Record<string, string> }) =>
    playwright.request.newContext(options);

async function openScene(page: Page, sceneId: string): Promise<void> {
  await page.goto(`/#/scenes/${sceneId}`);
  // The scene page loads the photo, the 3D scene and the model: slow on a busy machine.
  await expect(page.getByTestId("object-table")).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId("workflow-state")).not.toBeEmpty();
}

test("accounts, next scene by uncertainty, submit, reject with a comment, resubmit, accept, dashboard", async ({
  page,
  playwright,
}) => {
  const newContext = requestContexts(playwright);
  const admin = await apiAs(newContext, ADMIN);

  // Nothing is reachable without logging in on this server.
  const anonymous = await newContext({ baseURL: WORKFLOW_URL });
  expect((await anonymous.get("/api/scenes")).status()).toBe(401);
  expect((await anonymous.get("/api/auth/me")).status()).toBe(401);
  await anonymous.dispose();

  // Two scenes, both predicted by the pipeline: a real photo and a synthetic room.
  const photoId = await importFolder(admin, REAL_PHOTO, "img.jpg", "im3d-3 photo");
  const roomId = await importFolder(admin, synthesize(12), "img.png", "synthetic room 12");
  const predicted = await listScenes(admin);
  expect(predicted.map((s) => s.state)).toEqual(["predicted", "predicted"]);
  // "Next scene" must take the one the pipeline is least sure of first.
  const [first, second] = [...predicted].sort(
    (a, b) => (b.uncertainty ?? 0) - (a.uncertainty ?? 0),
  );
  if (!first || !second) throw new Error("two scenes were imported");
  expect(first.uncertainty).not.toBe(second.uncertainty);

  // The admin logs in and creates an annotator and a reviewer.
  await page.goto("/");
  await expect(page.getByTestId("login-form")).toBeVisible();
  await shot(page, "login");
  await page.getByTestId("login-name").fill(ADMIN.name);
  await page.getByTestId("login-password").fill("not the password");
  await page.getByTestId("login-submit").click();
  await expect(page.getByTestId("login-error")).toHaveText("wrong user name or password");
  await logIn(page, ADMIN.name, ADMIN.password);
  await expect(page.getByTestId("current-role")).toHaveText("(admin)");
  // The accounts are one click away in the header, the dashboard opened at them.
  await page.getByTestId("accounts-link").click();
  await expect(page.getByTestId("accounts")).toBeInViewport();
  for (const [user, role] of [
    [ANNOTATOR, "annotator"],
    [REVIEWER, "reviewer"],
  ] as const) {
    await page.getByTestId("new-user-name").fill(user.name);
    await page.getByTestId("new-user-role").selectOption(role);
    await page.getByTestId("new-user-password").fill(user.password);
    await page.getByTestId("new-user-submit").click();
    await expect(page.getByTestId("accounts-message")).toHaveText(`Added ${user.name} (${role}).`);
    await expect(page.getByTestId(`account-${user.name}`)).toBeVisible();
  }
  // The only admin cannot be demoted or disabled: its row says so instead of asking first.
  await expect(page.getByTestId(`disable-account-${ADMIN.name}`)).toBeDisabled();
  await expect(page.getByTestId(`role-select-${ADMIN.name}`)).toBeDisabled();
  await expect(page.getByTestId(`role-select-${ADMIN.name}`)).toHaveAttribute(
    "title",
    `${ADMIN.name} is the only admin: make another account admin first`,
  );
  // Disabling an account asks first; enabling it again does not.
  page.once("dialog", (dialog) => void dialog.accept());
  await page.getByTestId(`disable-account-${REVIEWER.name}`).click();
  await expect(page.getByTestId(`account-status-${REVIEWER.name}`)).toContainText("disabled");
  await expect(page.getByTestId("accounts-message")).toHaveText(`${REVIEWER.name} is disabled.`);
  await page.getByTestId(`enable-account-${REVIEWER.name}`).click();
  await expect(page.getByTestId(`account-status-${REVIEWER.name}`)).toHaveText("active");
  // Making someone an admin asks first: declined, the role stays.
  page.once("dialog", (dialog) => void dialog.dismiss());
  await page.getByTestId(`role-select-${REVIEWER.name}`).selectOption("admin");
  await expect(page.getByTestId(`role-select-${REVIEWER.name}`)).toHaveValue("reviewer");
  // A new password is typed into a password field in the row (the same one, for what follows).
  await page.getByTestId(`reset-password-${REVIEWER.name}`).click();
  const newPassword = page.getByTestId(`new-password-${REVIEWER.name}`);
  await expect(newPassword).toHaveAttribute("type", "password");
  await newPassword.fill(REVIEWER.password);
  await page.getByTestId(`set-password-${REVIEWER.name}`).click();
  await expect(page.getByTestId("accounts-message")).toHaveText(
    `New password set for ${REVIEWER.name}; their sessions ended.`,
  );
  await expect(newPassword).toBeHidden();
  // A weak password is refused with the server's reason.
  await page.getByTestId("new-user-name").fill("weak");
  await page.getByTestId("new-user-password").fill("aaaaaaaaaaaa");
  await page.getByTestId("new-user-submit").click();
  await expect(page.getByTestId("accounts-message")).toContainText("different characters");
  await expect(page.getByTestId("account-weak")).toHaveCount(0);
  await shot(page, "accounts");
  // A name the browser refuses (its own bubble) clears that older answer.
  await page.getByTestId("new-user-name").fill("Not Allowed");
  await page.getByTestId("new-user-submit").click();
  await expect(page.getByTestId("accounts-message")).toHaveText("");
  await page.getByTestId("new-user-name").fill("");
  await logOut(page);

  // The annotator takes the next scene twice, corrects a supporter in each and submits.
  await logIn(page, ANNOTATOR.name, ANNOTATOR.password);
  await expect(page.getByTestId("current-role")).toHaveText("(annotator)");
  await expect(page.getByTestId(`scene-state-${photoId}`)).toHaveText("predicted");
  await expect(page.getByTestId(`scene-state-${roomId}`)).toHaveText("predicted");
  await shot(page, "list-annotator");
  await expect(page.getByTestId("next-review")).toBeHidden(); // reviewing is not theirs
  // Nor is retraining or choosing the active model: the models page says so and offers neither.
  await page.goto("/#/models");
  await expect(page.getByTestId("models-admin-only")).toBeVisible();
  await expect(page.getByTestId("model-list")).toBeVisible();
  await expect(page.getByTestId("retrain-form")).toBeHidden();
  await expect(page.locator("[data-testid^='promote-']")).toHaveCount(0);
  await page.goto("/#/");
  await page.getByTestId("next-scene").click();
  await expect(page).toHaveURL(new RegExp(`#/scenes/${first.id}$`));
  await expect(page.getByTestId("object-table")).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  await expect(page.getByTestId("workflow-assignee")).toContainText(ANNOTATOR.name);
  // Annotators neither accept nor reject.
  await expect(page.getByTestId("workflow-accept")).toBeHidden();
  await correctASupporter(page, admin, first.id);
  await expect(page.getByTestId("workflow-submit")).toBeEnabled();
  await shot(page, "annotating");
  // The corrected supporter may be one the model is sure of otherwise: then submit asks first.
  await submitAnsweringYes(page);
  // Submitted work is locked: the server refuses edits until a reviewer decides.
  await expect(page.getByTestId("workflow-note")).toContainText("Submitted");
  await expectReadOnly(page, first.id, "Submitted for review — read only");
  await shot(page, "read-only");
  // Submitted too soon: taken back before any review, it is theirs to change again.
  await page.getByTestId("workflow-withdraw").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  await expect(page.getByTestId("workflow-events").locator("li").last()).toContainText(
    `${ANNOTATOR.name} took the submission back`,
  );
  await expect(page.getByTestId("workflow-withdraw")).toBeHidden();
  await submitAnsweringYes(page);
  await expect(page.getByTestId("workflow-withdraw")).toBeVisible();

  await page.keyboard.press(">"); // the next scene, from the scene page
  await expect(page).toHaveURL(new RegExp(`#/scenes/${second.id}$`));
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  // Taken by mistake: given back (after a confirmation), it waits for an annotator again.
  page.once("dialog", (dialog) => void dialog.accept());
  await page.getByTestId("workflow-release").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("predicted");
  await expect(page.getByTestId("workflow-events").locator("li").last()).toContainText(
    `${ANNOTATOR.name} gave it back`,
  );
  await page.getByTestId("workflow-take").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  // An admin sets the annotator's password (the same one, for the steps below), which ends
  // their session: the next save is refused, they log in again over the page, their name
  // filled in, and the edit is saved by itself after the login.
  const reset = await admin.post(`/api/users/${ANNOTATOR.name}/password`, {
    data: { password: ANNOTATOR.password },
  });
  expect(reset.status()).toBe(204);
  const edited = await correctASupporterUnsaved(page, admin, second.id);
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("login-overlay-reason")).toContainText("password was changed");
  await expect(page.getByTestId("login-name")).toHaveValue(ANNOTATOR.name);
  await page.getByTestId("login-password").fill(ANNOTATOR.password);
  await page.getByTestId("login-submit").click();
  await expect(page.getByTestId("login-overlay")).toHaveCount(0);
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  const afterLogin = (await (await admin.get(`/api/scenes/${second.id}`)).json()) as SceneDocument;
  expect(afterLogin.scene.supports?.find((s) => s.child === edited.child)?.parent).toBe(
    edited.target,
  );
  await page.locator("body").click({ position: { x: 5, y: 5 } }); // keys go to the page
  // One keystroke would lock the scene: it asks first (declined, nothing happens). The
  // question comes after a request, so each one is awaited before the next key.
  const declined = page.waitForEvent("dialog");
  await page.keyboard.press("Shift+Enter");
  await (await declined).dismiss();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  const accepted = page.waitForEvent("dialog");
  await page.keyboard.press("Shift+Enter");
  const question = await accepted;
  expect(question.message()).toMatch(/Submit/);
  await question.accept();
  await expect(page.getByTestId("workflow-state")).toHaveText("submitted");
  // Nothing is left to take.
  await page.goto("/#/");
  await page.getByTestId("next-scene").click();
  await expect(page.getByTestId("next-scene-message")).toContainText("no scene is waiting");
  await logOut(page);

  // The reviewer rejects the first with a comment and accepts the second.
  await logIn(page, REVIEWER.name, REVIEWER.password);
  await page.getByTestId("state-filter").selectOption("submitted");
  await expect(page.getByTestId("scene-list").locator("tbody tr")).toHaveCount(2);
  await expect(page.getByTestId(`scene-assignee-${first.id}`)).toHaveText(ANNOTATOR.name);
  await shot(page, "list-reviewer");
  // "Next to review" (its key on the list: R) opens the submitted scene waiting longest, and
  // takes nothing.
  await expect(page.getByTestId("next-review")).toHaveAttribute("title", /\(R\)$/);
  await page.keyboard.press("R");
  await expect(page).toHaveURL(new RegExp(`#/scenes/${first.id}$`));
  await expect(page.getByTestId("object-table")).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId("workflow-state")).toHaveText("submitted");
  await expect(page.getByTestId("workflow-submit")).toBeHidden();
  // The reviewer judges it as submitted: read only for them too.
  await expect(page.getByTestId("read-only-reason")).toHaveText("Submitted for review — read only");
  // Where to start: what the annotator changed since taking the scene.
  const takenAt = (await workflowOf(admin, first.id)).events.findLast(
    (e) => e.to_state === "in_annotation" && e.action !== "withdraw",
  )?.revision;
  await expect(page.getByTestId("since-rejection")).toHaveText(
    `What ${ANNOTATOR.name} changed since taking it (revision ${takenAt})`,
  );
  await page.getByTestId("workflow-reject").click();
  await page.getByTestId("reject-send").click(); // no comment: refused in the page
  await expect(page.getByTestId("workflow-error")).toContainText("Say what went wrong");
  await expect(page.getByTestId("workflow-state")).toHaveText("submitted");
  const comment = "Check the objects on the floor: one of them stands on the bed.";
  await page.getByTestId("reject-comment").fill(comment);
  await page.getByTestId("reject-send").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("rejected");
  await expect(page.getByTestId("review-comment-text")).toHaveText(comment);
  await shot(page, "rejected");

  // From the scene page, Shift+Right opens the next one waiting: the second.
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  await page.keyboard.press("Shift+ArrowRight");
  await expect(page).toHaveURL(new RegExp(`#/scenes/${second.id}$`));
  await expect(page.getByTestId("workflow-accept")).toBeVisible();
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  page.once("dialog", (dialog) => void dialog.accept()); // asked first, as the keystroke is final
  await page.keyboard.press("Shift+Enter"); // accept
  await expect(page.getByTestId("workflow-state")).toHaveText("accepted");
  await logOut(page);

  // The annotator gets the rejected scene back first, sees the comment, fixes and resubmits.
  await logIn(page, ANNOTATOR.name, ANNOTATOR.password);
  await expect(page.getByTestId(`scene-state-${first.id}`)).toHaveText("rejected");
  // Said above the list, with the way to it: "Mine to do" lists it alone (the accepted one is
  // done, the others are not theirs).
  await expect(page.getByTestId("sent-back-notice")).toContainText(
    `1 scene was sent back to you by a reviewer: ${first.name}.`,
  );
  await page.getByTestId("show-sent-back").click();
  await expect(page.getByTestId("state-filter")).toHaveValue("mine");
  await expect(page.locator("[data-testid^='scene-state-']")).toHaveCount(1);
  await expect(page.getByTestId(`scene-state-${first.id}`)).toHaveText("rejected");
  await page.getByTestId("state-filter").selectOption("");
  await page.getByTestId("next-scene").click();
  await expect(page).toHaveURL(new RegExp(`#/scenes/${first.id}$`));
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  // Editable again: no banner, the editors and their keys are on.
  await expect(page.getByTestId("read-only-banner")).toBeHidden();
  await expect(page.locator("[data-testid^='supporter-select-']").first()).toBeEnabled();
  await expect(page.getByTestId("layout-toggle")).toBeEnabled();
  await expect(page.getByTestId("undo-button")).toBeDisabled(); // nothing to undo yet
  // The reviewer's comment stays in view while the annotator fixes the scene.
  await expect(page.getByTestId("review-comment-text")).toHaveText(comment);
  await expect(page.getByTestId("review-comment")).toContainText(`Rejected by ${REVIEWER.name}`);
  await page.getByTestId("workflow-bar").locator("details").first().click();
  await expect(page.getByTestId("workflow-events")).toContainText(comment);
  await shot(page, "comment-seen");
  await correctASupporter(page, admin, first.id);
  await submitAnsweringYes(page);
  await expect(page.getByTestId("review-comment")).toBeHidden();
  await logOut(page);

  // The reviewer looks first at what changed since sending it back, then accepts it; the
  // dashboard shows the counts.
  await logIn(page, REVIEWER.name, REVIEWER.password);
  await openScene(page, first.id);
  const rejectedAt = (await workflowOf(admin, first.id)).events.findLast(
    (e) => e.action === "reject",
  )?.revision;
  await expect(page.getByTestId("since-rejection")).toHaveText(
    `What changed since it was sent back (revision ${rejectedAt})`,
  );
  // What she asked for is still in view, to check it was done.
  await expect(page.getByTestId("review-comment")).toContainText(
    `Asked when sent back by ${REVIEWER.name} (revision ${rejectedAt}): ${comment}`,
  );
  await page.getByTestId("since-rejection").click();
  const since = page.getByTestId(`revision-diff-${rejectedAt}`);
  await expect(since).toBeVisible();
  await expect(since).toBeInViewport();
  // The annotator's correction: one support changed.
  await expect(since.locator("li[data-child]")).not.toHaveCount(0);
  await expect(since).not.toContainText("nothing has changed since");
  // Accepting is final: a click asks first too, saying how much a person checked.
  let asked = "";
  page.once("dialog", (dialog) => {
    asked = dialog.message();
    void dialog.accept();
  });
  await page.getByTestId("workflow-accept").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("accepted");
  expect(asked).toMatch(/^Accept this scene\? .* objects? ha(s|ve) a supporter set by a person\.$/);
  await page.getByTestId("dashboard-link").click();
  await expect(page.getByTestId("state-count-accepted")).toHaveText("2");
  for (const state of ["new", "predicted", "in_annotation", "submitted", "rejected"]) {
    await expect(page.getByTestId(`state-count-${state}`)).toHaveText("0");
  }
  await expect(page.getByTestId(`person-${ANNOTATOR.name}-submitted`)).toHaveText("3");
  await expect(page.getByTestId(`person-${ANNOTATOR.name}-accepted`)).toHaveText("2");
  await expect(page.getByTestId(`person-${ANNOTATOR.name}-rejected`)).toHaveText("1");
  await expect(page.getByTestId(`person-${REVIEWER.name}-reviewed`)).toHaveText("3");
  await expect(page.getByTestId("accounts")).toHaveCount(0); // accounts are for admins
  await shot(page, "dashboard");

  // The server kept who did what, and when.
  const history = await workflowOf(admin, first.id);
  expect(history.events.map((e) => [e.action, e.actor])).toEqual([
    ["import", ADMIN.name],
    ["predict", "pipeline"],
    ["claim", ANNOTATOR.name],
    ["submit", ANNOTATOR.name],
    ["withdraw", ANNOTATOR.name],
    ["submit", ANNOTATOR.name],
    ["reject", REVIEWER.name],
    ["reopen", ANNOTATOR.name],
    ["submit", ANNOTATOR.name],
    ["accept", REVIEWER.name],
  ]);

  // A page that may only watch follows someone else's saves: the reviewer has a new scene open
  // while the annotator takes it and saves from another client; within the workflow check's
  // 10 s the page shows their revision, without a reload.
  const thirdId = await importFolder(admin, synthesize(14), "img.png", "synthetic room 14");
  await openScene(page, thirdId);
  const shown = (await (await admin.get(`/api/scenes/${thirdId}`)).json()) as SceneDocument;
  await expect(page.getByTestId("scene-meta")).toContainText(`revision ${shown.revision}`);
  const annotator = await apiAs(newContext, ANNOTATOR);
  expect((await annotator.post(`/api/scenes/${thirdId}/take`)).status()).toBe(200);
  const moved = (shown.scene.supports ?? []).find((s) => s.parent !== "wall");
  if (!moved) throw new Error("the synthetic room has a support to change");
  const saved = await annotator.post(`/api/scenes/${thirdId}/edits`, {
    data: {
      base_revision: shown.revision,
      author: ANNOTATOR.name,
      edits: [{ kind: "set_support", child: moved.child, parent: "wall", type: "behind" }],
    },
  });
  expect(saved.status(), await saved.text()).toBe(200);
  await expect(page.getByTestId("scene-meta")).toContainText(`revision ${shown.revision + 1}`, {
    timeout: 20_000,
  });
  await expect(page.getByTestId(`supporter-select-${moved.child}`)).toHaveValue("wall");
  // The dashboard follows too: the annotator submits, the open dashboard counts it.
  await page.getByTestId("dashboard-link").click();
  await expect(page.getByTestId("state-count-in_annotation")).toHaveText("1");
  const submitted = await annotator.post(`/api/scenes/${thirdId}/submit`, {
    data: { revision: shown.revision + 1 },
  });
  expect(submitted.status(), await submitted.text()).toBe(200);
  await expect(page.getByTestId("state-count-submitted")).toHaveText("1", { timeout: 20_000 });
  await expect(page.getByTestId("state-count-in_annotation")).toHaveText("0");
  await annotator.dispose();
  await admin.dispose();
});

test("logging out saves the last edit first; unsaved edits stay with their author in a shared browser", async ({
  page,
  playwright,
}) => {
  const newContext = requestContexts(playwright);
  const admin = await apiAs(newContext, ADMIN);
  const author = { name: "olga", password: "willow-anchor-48-dune" };
  const made = await admin.post("/api/users", { data: { ...author, role: "annotator" } });
  expect(made.status(), await made.text()).toBe(201);
  const sceneId = await importFolder(admin, synthesize(14), "img.png", "shared browser room");

  await page.goto("/");
  await logIn(page, author.name, author.password);
  await openScene(page, sceneId);
  await page.getByTestId("workflow-take").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  // An edit, and at once Log out: it is saved under her session before it ends.
  const first = await correctASupporterUnsaved(page, admin, sceneId);
  await logOut(page);
  const saved = (await (await admin.get(`/api/scenes/${sceneId}`)).json()) as SceneDocument;
  expect(saved.scene.supports?.find((s) => s.child === first.child)).toMatchObject({
    parent: first.target,
    author: author.name,
  });

  // An edit the server never gets (every save fails) stays in this browser as her draft.
  await logIn(page, author.name, author.password);
  await page.route("**/api/scenes/*/edits", (route) => route.abort("failed"));
  await openScene(page, sceneId);
  const second = await correctASupporterUnsaved(page, admin, sceneId);
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "error", {
    timeout: 20_000,
  });
  await logOut(page);
  await page.unroute("**/api/scenes/*/edits");

  // The admin logs in on the same browser: Olga's unsaved edit is not offered to him.
  await logIn(page, ADMIN.name, ADMIN.password);
  await openScene(page, sceneId);
  await expect(page.getByTestId("recovery-banner")).toBeHidden();
  await expect(page.getByTestId("save-status")).not.toHaveAttribute("data-state", "dirty");
  await logOut(page);

  // Back as Olga: it is offered to her, and restoring it saves it under her name.
  await logIn(page, author.name, author.password);
  await openScene(page, sceneId);
  const banner = page.getByTestId("recovery-banner");
  await expect(banner).toBeVisible();
  await expect(banner).toContainText(second.child);
  await page.keyboard.press("Shift+U");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  const restored = (await (await admin.get(`/api/scenes/${sceneId}`)).json()) as SceneDocument;
  expect(restored.scene.supports?.find((s) => s.child === second.child)).toMatchObject({
    parent: second.target,
    author: author.name,
  });
  await admin.dispose();
});
