import { fileURLToPath } from "node:url";
import { defineConfig } from "vite";

// The backend (`holiscene serve`) serves the built app from frontend/dist and the API under
// /api; in development Vite serves the app and forwards /api to it.
const backend = process.env.HOLISCENE_API_URL ?? "http://127.0.0.1:8000";

export default defineConfig({
  server: {
    proxy: { "/api": { target: backend, changeOrigin: false } },
  },
  preview: {
    proxy: { "/api": { target: backend, changeOrigin: false } },
  },
  build: {
    target: "es2022",
    sourcemap: true,
    chunkSizeWarningLimit: 1024,
    rolldownOptions: {
      // The workbench, and pages that run the Relation Network and the object detector in the
      // browser (for their end-to-end tests and benchmarks). onnxruntime-web's wasm file is
      // emitted beside them.
      input: {
        main: fileURLToPath(new URL("index.html", import.meta.url)),
        relationCheck: fileURLToPath(new URL("relation-check.html", import.meta.url)),
        detectorCheck: fileURLToPath(new URL("detector-check.html", import.meta.url)),
      },
    },
  },
});
