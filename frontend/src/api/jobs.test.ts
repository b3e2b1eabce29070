// Polling a job is something the page does by itself: every poll carries the background
// header, so the server does not count it as activity and a forgotten tab still idles out.
import type { Job } from "@holiscene/schema";
import { afterEach, describe, expect, it, vi } from "vitest";
import { BACKGROUND_HEADER } from "./client";
import { pollJob } from "./jobs";

const job = (status: Job["status"]): Job =>
  ({ id: "job-1", kind: "pipeline", status, scene_id: "s1" }) as unknown as Job;

afterEach(() => {
  vi.unstubAllGlobals();
});

describe("pollJob", () => {
  it("sends every poll as a background request", async () => {
    const answers = [job("running"), job("succeeded")];
    const fetchMock = vi.fn(async (_url: string, _init?: RequestInit) =>
      Response.json(answers.shift()),
    );
    vi.stubGlobal("fetch", fetchMock);

    const final = await pollJob(job("queued"), { intervalMs: 0 });

    expect(final.status).toBe("succeeded");
    expect(fetchMock).toHaveBeenCalledTimes(2);
    for (const [url, init] of fetchMock.mock.calls) {
      expect(url).toBe("/api/jobs/job-1");
      expect(new Headers(init?.headers).get(BACKGROUND_HEADER)).toBe("1");
    }
  });
});
