// From another machine the viewer's loopback address is the reviewer's own: the page says how
// to reach it; on the server itself it says nothing.
import { describe, expect, it } from "vitest";
import { remoteViewerNote } from "./viserLink";

describe("remoteViewerNote", () => {
  it("tells a reviewer on another machine to forward the viewer's port", () => {
    const note = remoteViewerNote("http://127.0.0.1:8123/", "lab.example");
    expect(note).toContain("ssh -L 8123:127.0.0.1:8123 lab.example");
    expect(note).toContain("open http://127.0.0.1:8123/");
    expect(remoteViewerNote("http://127.0.0.1:8123/", "localhost")).toBeNull();
    expect(remoteViewerNote("http://127.0.0.1:8123/", "127.0.0.1")).toBeNull();
  });
});
