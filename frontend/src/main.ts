// Entry point: the author field and the hash router.
import "./styles.css";
import { el } from "./dom";
import { confirmLeave, parseRoute } from "./router";
import { bindAuthorInput } from "./state/author";
import { mountShortcutHelp } from "./views/help/shortcutHelp";
import { mountModelsPage } from "./views/models/modelsPage";
import { mountScenePage } from "./views/scene/scenePage";
import { mountSceneList } from "./views/sceneList/sceneListView";

const app = document.querySelector<HTMLElement>("#app");
const authorInput = document.querySelector<HTMLInputElement>("#author-input");
if (!app || !authorInput) throw new Error("index.html lacks #app or #author-input");
bindAuthorInput(authorInput);
mountShortcutHelp(document.body);

function mount(root: HTMLElement): () => void {
  const route = parseRoute(window.location.hash);
  document.body.dataset.page = route.page;
  switch (route.page) {
    case "list":
      document.title = "HoliScene";
      return mountSceneList(root);
    case "scene":
      document.title = `${route.sceneId} · HoliScene`;
      return mountScenePage(root, route.sceneId);
    case "models":
      document.title = "Models · HoliScene";
      return mountModelsPage(root);
    case "unknown":
      document.title = "HoliScene";
      root.replaceChildren(
        el(
          "p",
          { className: "page-message" },
          "No such page. ",
          el("a", { text: "All scenes", attrs: { href: "#/" } }),
        ),
      );
      return () => {};
  }
}

let dispose = mount(app);
let shownHash = window.location.hash;
window.addEventListener("hashchange", () => {
  if (!confirmLeave()) {
    // Stay: put the address back without another hashchange.
    history.replaceState(null, "", shownHash || "#/");
    return;
  }
  shownHash = window.location.hash;
  dispose();
  dispose = mount(app);
  app.focus({ preventScroll: true });
  window.scrollTo(0, 0);
});
