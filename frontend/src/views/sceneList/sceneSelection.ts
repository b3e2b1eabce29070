// Scenes ticked in the list, and "Download selected": one zip of their files, as a folder per
// scene or in one of the export formats of `holiscene export`. Only scenes the list shows stay
// ticked (a filter or a refresh drops the others), so what is ticked on the page is what is
// downloaded.
import type { SceneArchiveRequest } from "@holiscene/schema";
import { downloadArchive } from "../../api/downloads";
import { button, el } from "../../dom";
import { plural } from "../../state/sceneSession";
import "./sceneSelection.css";

interface DownloadFormat {
  value: SceneArchiveRequest["format"];
  label: string;
  /** What the zip then holds (the menu's tooltip). */
  holds: string;
}

const FOLDERS: DownloadFormat = {
  value: null,
  label: "HoliScene folders",
  holds:
    "a folder per scene: scene.json, COCO JSON, the photo, scene.glb and the labels as an " +
    "input folder; Import a dataset takes it back",
};

/** The formats offered: HoliScene's own folders, then those of `holiscene export`. */
const DOWNLOAD_FORMATS: readonly DownloadFormat[] = [
  FOLDERS,
  {
    value: "coco",
    label: "COCO dataset",
    holds: "annotations.json (NYU-40 categories, masks as RLE, supports) and images/",
  },
  {
    value: "scene",
    label: "Input folders",
    holds: "a folder per scene as holiscene infer reads it, with scene.json and scene.glb",
  },
  {
    value: "total3d",
    label: "Total3D demo",
    holds: "Total3DUnderstanding's demo input and results per scene",
  },
  {
    value: "total3d-training",
    label: "Total3D training",
    holds: "Total3DUnderstanding's data/sunrgbd/ layout for its training code",
  },
  {
    value: "relation-training",
    label: "Support pairs",
    holds: "the Relation Network's inputs and the support pairs people labelled",
  },
  {
    value: "nyu-supports",
    label: "NYU Depth v2 .mat",
    holds: "nyu_depth_v2_labeled.mat and support_labels.mat (the scenes must share one size)",
  },
];

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
  private readonly format = el(
    "select",
    {
      testid: "download-format",
      attrs: { "aria-label": "Format of the download" },
    },
    ...DOWNLOAD_FORMATS.map((f) =>
      el("option", { text: f.label, attrs: { value: f.value ?? "", title: f.holds } }),
    ),
  );
  readonly element = el(
    "div",
    { className: "scene-selection" },
    this.format,
    this.button,
    this.status,
  );

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
    this.format.addEventListener("change", () => this.update());
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
    const chosen = this.chosenFormat();
    this.button.title = `One zip: ${chosen.holds}`;
    this.format.title = chosen.holds;
    this.format.disabled = this.busy;
  }

  private chosenFormat(): DownloadFormat {
    const value = this.format.value || null;
    return DOWNLOAD_FORMATS.find((f) => f.value === value) ?? FOLDERS;
  }

  private async download(): Promise<void> {
    const [first, ...rest] = this.order.filter((id) => this.selected.has(id)); // list order
    if (first === undefined) return;
    this.busy = true;
    this.status.textContent = "";
    this.status.classList.remove("is-error");
    this.update();
    try {
      await downloadArchive([first, ...rest], this.chosenFormat().value);
    } catch (error) {
      this.status.classList.add("is-error");
      this.status.textContent = `Could not download: ${error instanceof Error ? error.message : String(error)}`;
    } finally {
      this.busy = false;
      this.update();
    }
  }
}
