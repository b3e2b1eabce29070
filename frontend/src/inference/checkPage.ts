// The page a person opens to try a model in the browser (detector-check.html,
// relation-check.html): a button loads the app's active model and says how long it took.
import { button, el } from "../dom";

export interface CheckPage {
  /** testid prefix: "detector-check", "relation-check". */
  id: string;
  title: string;
  about: string;
  /** "detector", "model". */
  what: string;
  /** Loads the model; resolves to what the status line says once it is ready. */
  load(): Promise<string>;
}

export function mountCheckPage(page: CheckPage): void {
  const status = el("p", { testid: `${page.id}-status`, text: `No ${page.what} loaded yet.` });
  const loadButton = button(`Load the active ${page.what}`, {
    testid: `${page.id}-load`,
    onClick: () => {
      loadButton.disabled = true;
      status.textContent = "Loading…";
      page
        .load()
        .then((ready) => {
          status.textContent = ready;
        })
        .catch((error: unknown) => {
          const message = error instanceof Error ? error.message : String(error);
          status.textContent = `Could not load the ${page.what}: ${message}`;
        })
        .finally(() => {
          loadButton.disabled = false;
        });
    },
  });
  document
    .querySelector("#app")
    ?.replaceChildren(
      el("h1", { text: page.title }),
      el("p", { text: page.about }),
      loadButton,
      status,
    );
}
