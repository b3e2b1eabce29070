// The server's GrabCut steered by a person's strokes (POST /api/scenes/{id}/mask-refine): a box
// and foreground/background strokes in, a mask out. Nothing is stored; the mask tools send the
// answer as a set_mask edit when the person keeps it.
import type { MaskRefineRequest, MaskRefineResult } from "@holiscene/schema";
import { jsonBody, request } from "./client";

export function refineMask(sceneId: string, body: MaskRefineRequest): Promise<MaskRefineResult> {
  return request<MaskRefineResult>(
    `/scenes/${encodeURIComponent(sceneId)}/mask-refine`,
    jsonBody(body),
  );
}
