// The page's confirm questions (window.confirm), read and answered by a test.
import type { Page } from "@playwright/test";

/** The message of the page's next dialog, once it is answered Yes ("accept") or No. */
export function nextDialog(page: Page, answer: "accept" | "dismiss"): Promise<string> {
  return new Promise<string>((resolve) =>
    page.once("dialog", (dialog) => {
      resolve(dialog.message());
      void (answer === "accept" ? dialog.accept() : dialog.dismiss());
    }),
  );
}
