// Test fixtures (unit tests only): scene objects, a scene document holding them, and a session
// on it whose drafts live in memory.
import type { SceneDocument, SceneObject, SupportRelation } from "@holiscene/schema";
import { DraftStore } from "../state/draftStore";
import { SceneSession } from "../state/sceneSession";
import { MemoryStorage } from "./memoryStorage";

type Box = [number, number, number, number];

export const sceneObject = (id: string, cls = "chair", bbox: Box = [0, 0, 10, 10]): SceneObject =>
  ({ id, class: cls, bbox }) as unknown as SceneObject;

/** Scene "s1" on a 100 x 100 photo (or `size`) with these objects and supports. */
export function sceneDocument(
  objects: SceneObject[],
  supports: SupportRelation[] = [],
  { revision = 1, size = 100 }: { revision?: number; size?: number } = {},
): SceneDocument {
  return {
    scene_id: "s1",
    revision,
    updated_at: "2026-01-01T00:00:00Z",
    scene: {
      schema_version: 1,
      name: "test",
      image: { file: "img.png", width: size, height: size },
      objects,
      supports,
    },
  } as unknown as SceneDocument;
}

/** A session on `doc` keeping its drafts in `storage` (by default a fresh one in memory). */
export const sessionOn = (doc: SceneDocument, storage: Storage | null = new MemoryStorage()) =>
  new SceneSession(doc, { drafts: new DraftStore(storage) });
