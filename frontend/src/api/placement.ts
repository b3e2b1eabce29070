// Placement jobs: the stages after the room layout, run again on a scene's stored revision
// (after a person moved the layout), writing a new revision.
import type { Job } from "@holiscene/schema";
import { request } from "./client";

export const startPlacement = (sceneId: string) =>
  request<Job>(`/scenes/${encodeURIComponent(sceneId)}/placement-jobs`, { method: "POST" });
