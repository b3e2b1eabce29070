// "Re-place objects": a placement job on the scene's saved revision (the stages after the
// room layout: objects into 3D, supports, meshes), followed until it ends; on success the
// session loads the revision it wrote. The layout editor and the 3D panel's notice share it.
import type { Job } from "@holiscene/schema";
import { pollJob } from "../api/jobs";
import { startPlacement } from "../api/placement";
import type { SceneSession } from "../state/sceneSession";

export async function replaceObjects(
  session: SceneSession,
  options: { signal?: AbortSignal; onUpdate?: (job: Job) => void } = {},
): Promise<Job> {
  const started = await startPlacement(session.sceneId);
  options.onUpdate?.(started);
  const job = await pollJob(started, options);
  if (job.status === "succeeded") await session.reloadLatest();
  return job;
}
