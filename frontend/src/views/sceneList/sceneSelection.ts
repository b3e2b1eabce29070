// Scenes ticked in the list, and "Download selected": one zip of their files. Only scenes the
// list shows stay ticked (a filter or a refresh drops the others), so what is ticked on the
// page is what is downloaded.
import { downloadArchive } from "../../api/downloads";
import { button, el } from "../../dom";
import { plural } from "../../state/sceneSession";
import "./sceneSelection.css";

export class SceneSelection {
  private readonly selected = new Set<string>();
  private readonly boxes = new Map<string, HTMLInputElement>();
  private order: string[] = []; // the listed scenes, top to bottom
  private busy = false;
  /** The header's box: ticks or clears every listed scene. */
  readonly allBox = el("input", {
    testid: "select-all-scenes",
    attrs: { type: "checkbox", "aria-label": "Select every listed scene" },
  });
  private readonly button = button("", { testid: "download-selected", disabled: true });
  private readonly status = el("span", {
    className: "selection-status",
    testid: "download-selected-status",
    attrs: { role: "status" },
  });
  readonly element = el("div", { className: "scene-selection" }, this.button, this.status);

  constructor() {
    this.allBox.addEventListener("change", () => {
      for (const [id, box] of this.boxes) {
        box.checked = this.allBox.checked;
        if (this.allBox.checked) this.selected.add(id);
        else this.selected.delete(id);
      }
      this.update();
    });
    this.button.addEventListener("click", () => void this.download());
    this.update();
  }

  /** The row's box; call `listed` once every row of a refresh has its box. */
  checkbox(sceneId: string, name: string): HTMLInputElement {
    const box = el("input", {
      testid: `select-scene-${sceneId}`,
      attrs: { type: "checkbox", "aria-label": `Select ${name}` },
    });
    box.checked = this.selected.has(sceneId);
    box.addEventListener("change", () => {
      if (box.checked) this.selected.add(sceneId);
      else this.selected.delete(sceneId);
      this.update();
    });
    this.boxes.set(sceneId, box);
    return box;
  }

  /** The list now shows these scenes (each with a box from `checkbox`). */
  listed(sceneIds: string[]): void {
    this.order = sceneIds;
    const shown = new Set(sceneIds);
    for (const id of [...this.boxes.keys()]) if (!shown.has(id)) this.boxes.delete(id);
    for (const id of [...this.selected]) if (!shown.has(id)) this.selected.delete(id);
    this.update();
  }

  private update(): void {
    const count = this.selected.size;
    this.allBox.checked = count > 0 && count === this.boxes.size;
    this.allBox.indeterminate = count > 0 && count < this.boxes.size;
    this.button.disabled = this.busy || count === 0;
    this.button.textContent = this.busy
      ? "Preparing the zip…"
      : count === 0
        ? "Download selected"
        : `Download ${plural(count, "selected scene")} (zip)`;
    this.button.title =
      "One zip with a folder per scene: scene.json, COCO JSON, the photo, scene.glb and the " +
      "labels as an input folder; Import a dataset takes it back";
  }

  private async download(): Promise<void> {
    const [first, ...rest] = this.order.filter((id) => this.selected.has(id)); // list order
    if (first === undefined) return;
    this.busy = true;
    this.status.textContent = "";
    this.status.classList.remove("is-error");
    this.update();
    try {
      await downloadArchive([first, ...rest]);
    } catch (error) {
      this.status.classList.add("is-error");
      this.status.textContent = `Could not download: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      this.busy = false;
      this.update();
    }
  }
}
