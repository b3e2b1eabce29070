// "Export PNG": the 3D view as it is now, downloaded as a PNG file.
import { saveBlob } from "../../saveFile";

/** Download the canvas's current picture; `draw` renders a fresh frame into it first. */
export async function downloadCanvasPng(
  canvas: HTMLCanvasElement,
  fileName: string,
  draw: () => void,
): Promise<void> {
  draw(); // the drawing buffer is kept (preserveDrawingBuffer), so this frame is what is read
  const blob = await new Promise<Blob | null>((resolve) => canvas.toBlob(resolve, "image/png"));
  if (!blob) throw new Error("the browser could not encode the 3D view as PNG");
  saveBlob(blob, fileName);
}

/** A file name safe on every system: letters, digits, '-', '_' and '.'. */
export function pngFileName(sceneName: string, revision: number): string {
  const base = sceneName.replace(/[^A-Za-z0-9._-]+/g, "-").replace(/^-+|-+$/g, "") || "scene";
  return `${base}-r${revision}-3d.png`;
}
