// onnxruntime-web's WASM build, shared by the models the browser runs (the Relation Network,
// the object detector). Loaded on first use as its own chunk (`import("onnxruntime-web/wasm")`);
// Vite emits its wasm file with the app, so the app serves it itself.
//
// The runtime works in its own worker (`proxy`): a scoring or a detection never holds the
// page's thread, so an edit's redraw does not wait behind one. A run hands its input tensors'
// buffers to that worker: callers must not read an input after passing it to `run`.

export type Ort = typeof import("onnxruntime-web/wasm");

let runtime: Promise<Ort> | null = null;

/** The runtime, configured for one thread in a worker of its own. */
export function loadRuntime(): Promise<Ort> {
  runtime ??= import("onnxruntime-web/wasm").then((ort) => {
    ort.env.wasm.numThreads = 1;
    ort.env.wasm.proxy = true;
    return ort;
  });
  runtime.catch(() => {
    runtime = null;
  });
  return runtime;
}
