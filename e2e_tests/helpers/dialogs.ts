// The page's confirm questions (window.confirm), read and answered by a test.
import type { Dialog, Page } from "@playwright/test";

/** The message of the page's next dialog, once it is answered Yes ("accept") or No. */
export function nextDialog(page: Page, answer: "accept" | "dismiss"): Promise<string> {
  return new Promise<string>((resolve) =>
    page.once("dialog", (dialog) => {
      resolve(dialog.message());
      void (answer === "accept" ? dialog.accept() : dialog.dismiss());
    }),
  );
}

/** Runs `act` answering Yes to every question it raises (what a submit asks depends on the
 * support model's scores, which a test does not fix); the questions asked, in order. */
export async function answeringYes(page: Page, act: () => Promise<void>): Promise<string[]> {
  const asked: string[] = [];
  const answer = (dialog: Dialog) => {
    asked.push(dialog.message());
    void dialog.accept();
  };
  page.on("dialog", answer);
  try {
    await act();
  } finally {
    page.off("dialog", answer);
  }
  return asked;
}
