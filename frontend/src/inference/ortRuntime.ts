// onnxruntime-web's WASM build, shared by the models the browser runs (the Relation Network,
// the object detector). Loaded on first use as its own chunk (`import("onnxruntime-web/wasm")`);
// Vite emits its wasm file with the app, so the app serves it itself.

export type Ort = typeof import("onnxruntime-web/wasm");

let runtime: Promise<Ort> | null = null;

/** The runtime, configured for one thread on the page's own thread. */
export function loadRuntime(): Promise<Ort> {
  runtime ??= import("onnxruntime-web/wasm").then((ort) => {
    ort.env.wasm.numThreads = 1;
    ort.env.wasm.proxy = false;
    return ort;
  });
  runtime.catch(() => {
    runtime = null;
  });
  return runtime;
}
