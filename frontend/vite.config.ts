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
  },
});
