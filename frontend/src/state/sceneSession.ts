// One scene being annotated: the loaded revision, the user's unsaved edits, saving, and
// what is hovered or selected. Views subscribe and redraw what a change concerns.
import type { SceneDocument, SceneObject } from "@holiscene/schema";
import { api } from "../api/client";
import { ConflictError } from "../api/errors";
import {
  describeEdit,
  type Edit,
  editProblem,
  isNoOp,
  type ShownSupport,
  shownSupports,
} from "./supportGraph";

export type SaveState =
  | { kind: "clean" }
  | { kind: "dirty" }
  | { kind: "saving" }
  | { kind: "saved"; revision: number }
  | { kind: "conflict"; baseRevision: number; currentRevision: number | null; message: string }
  | { kind: "error"; message: string };

/** What changed: the document, the unsaved edits, the save state, hover or selection. */
export type Change = "document" | "edits" | "save" | "hover" | "select";

export class SceneSession {
  doc: SceneDocument;
  saveState: SaveState = { kind: "clean" };
  hovered: string | null = null;
  selected: string | null = null;
  /** A message about the last reload (what happened to the unsaved edits). */
  notice: string | null = null;

  private readonly edits = new Map<string, Edit>();
  private readonly listeners = new Set<(change: Change) => void>();
  private shownCache: Map<string, ShownSupport> | null = null;

  constructor(doc: SceneDocument) {
    this.doc = doc;
  }

  get sceneId(): string {
    return this.doc.scene_id;
  }

  get objects(): SceneObject[] {
    return this.doc.scene.objects ?? [];
  }

  object(id: string): SceneObject | undefined {
    return this.objects.find((o) => o.id === id);
  }

  /** Unsaved edits, in the order they were made (one per object). */
  get pending(): Edit[] {
    return [...this.edits.values()];
  }

  isPending(child: string): boolean {
    return this.edits.has(child);
  }

  /** Every object's supporter as shown: saved supports with unsaved edits applied. */
  shown(): Map<string, ShownSupport> {
    this.shownCache ??= shownSupports(this.doc.scene.supports ?? [], this.edits.values());
    return this.shownCache;
  }

  subscribe(listener: (change: Change) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  /** Record an edit of one object's supporter; an edit back to the saved state cancels. */
  stage(edit: Edit): void {
    this.edits.delete(edit.child);
    if (!isNoOp(edit, this.doc.scene.supports ?? [])) this.edits.set(edit.child, edit);
    this.editsChanged();
  }

  discard(): void {
    this.edits.clear();
    this.notice = null;
    this.editsChanged();
  }

  hover(id: string | null): void {
    if (this.hovered === id) return;
    this.hovered = id;
    this.emit("hover");
  }

  select(id: string | null): void {
    this.selected = id;
    this.emit("select");
  }

  /** Send the unsaved edits, based on the loaded revision. They are kept unless saved. */
  async save(author: string): Promise<void> {
    const sent = this.pending;
    if (sent.length === 0 || this.saveState.kind === "saving") return;
    const [first, ...rest] = sent as [Edit, ...Edit[]];
    const baseRevision = this.doc.revision;
    this.setSaveState({ kind: "saving" });
    try {
      const doc = await api.postEdits(this.sceneId, {
        base_revision: baseRevision,
        author,
        edits: [first, ...rest],
      });
      for (const edit of sent) {
        if (this.edits.get(edit.child) === edit) this.edits.delete(edit.child);
      }
      this.notice = null;
      this.setDocument(doc);
      this.setSaveState(
        this.edits.size > 0 ? { kind: "dirty" } : { kind: "saved", revision: doc.revision },
      );
    } catch (error) {
      if (error instanceof ConflictError) {
        this.setSaveState({
          kind: "conflict",
          baseRevision,
          currentRevision: error.currentRevision,
          message: error.message,
        });
      } else {
        this.setSaveState({ kind: "error", message: errorText(error) });
      }
    }
  }

  /**
   * Load the latest revision and put the unsaved edits back on top of it, dropping only the
   * ones that no longer apply or that the latest revision already has (and saying so).
   */
  async reloadLatest(): Promise<void> {
    const previous = this.doc.revision;
    try {
      const [doc, revisions] = await Promise.all([
        api.getScene(this.sceneId),
        api.listRevisions(this.sceneId).catch(() => []),
      ]);
      const lines: string[] = [];
      const newer = revisions.filter((r) => r.number > previous);
      if (newer.length > 0) {
        lines.push(
          `Loaded revision ${doc.revision}. Changed since revision ${previous}: ` +
            newer.map((r) => `#${r.number} by ${r.author} (${r.summary})`).join("; "),
        );
      } else {
        lines.push(`Loaded revision ${doc.revision}.`);
      }
      for (const edit of this.pending) {
        const problem = editProblem(edit, doc.scene.objects ?? []);
        if (problem) {
          lines.push(`Dropped your edit "${describeEdit(edit)}": ${problem}.`);
          this.edits.delete(edit.child);
        } else if (isNoOp(edit, doc.scene.supports ?? [])) {
          lines.push(`Your edit "${describeEdit(edit)}" is already in revision ${doc.revision}.`);
          this.edits.delete(edit.child);
        }
      }
      if (this.edits.size > 0) {
        lines.push(
          `Your ${plural(this.edits.size, "unsaved change")} are applied on top; review and save again.`,
        );
      }
      this.notice = lines.join(" ");
      this.saveState = { kind: "clean" }; // the conflict is resolved; editsChanged() says what is left
      this.setDocument(doc);
      this.editsChanged();
    } catch (error) {
      this.setSaveState({ kind: "error", message: `Reload failed: ${errorText(error)}` });
    }
  }

  private setDocument(doc: SceneDocument): void {
    this.doc = doc;
    this.shownCache = null;
    this.emit("document");
  }

  private editsChanged(): void {
    this.shownCache = null;
    this.emit("edits");
    if (this.saveState.kind === "conflict" && this.edits.size > 0) return;
    if (this.saveState.kind === "saving") return;
    this.setSaveState(this.edits.size > 0 ? { kind: "dirty" } : { kind: "clean" });
  }

  private setSaveState(state: SaveState): void {
    this.saveState = state;
    this.emit("save");
  }

  private emit(change: Change): void {
    for (const listener of this.listeners) listener(change);
  }
}

export function plural(count: number, noun: string): string {
  return `${count} ${noun}${count === 1 ? "" : "s"}`;
}

function errorText(error: unknown): string {
  return error instanceof Error ? error.message : String(error);
}
