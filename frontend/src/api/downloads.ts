// Files to download: a scene's scene.json, scene.glb and COCO JSON, and several scenes as one
// zip (backend api/routes/downloads.py). The server names each file (Content-Disposition).
import type { SceneArchiveRequest } from "@holiscene/schema";
import { saveBlob } from "../saveFile";
import { BASE, jsonBody, requestFile } from "./client";

const sceneUrl = (sceneId: string) => `${BASE}/scenes/${encodeURIComponent(sceneId)}`;

export const downloadUrls = {
  sceneJson: (sceneId: string) => `${sceneUrl(sceneId)}/scene.json`,
  coco: (sceneId: string) => `${sceneUrl(sceneId)}/coco.json`,
  glb: (sceneId: string) => `${sceneUrl(sceneId)}/scene.glb`,
};

/** The revision whose pipeline or placement run made the scene's 3D scene (the server's
 * X-Glb-Revision), or null when there is none yet; asks for its first bytes only. */
export async function glbRevision(sceneId: string, signal?: AbortSignal): Promise<number | null> {
  // A range probe of a binary file, where 404 is an answer, not an error: a plain fetch.
  const response = await fetch(downloadUrls.glb(sceneId), {
    headers: { Range: "bytes=0-3" },
    signal,
  });
  void response.body?.cancel(); // the answer itself is all we wanted
  if (response.status === 404) return null;
  if (!response.ok) throw new Error(`scene.glb: ${response.status} ${response.statusText}`);
  return Number(response.headers.get("X-Glb-Revision") ?? Number.NaN);
}

/** Download the scenes as one zip: a folder per scene, or as `format` writes them. */
export async function downloadArchive(
  sceneIds: SceneArchiveRequest["scene_ids"],
  format: SceneArchiveRequest["format"] = null,
): Promise<void> {
  const body: SceneArchiveRequest = { scene_ids: sceneIds, format };
  const { blob, filename } = await requestFile("/scenes/archive", jsonBody(body));
  saveBlob(blob, filename ?? "holiscene-scenes.zip");
}
