// A check page running a model with onnxruntime-web must need nothing from outside the app:
// every request stays on the app's origin, and the runtime's wasm comes from the app's assets,
// served as wasm (the app works offline and its CSP allows nothing else).
import { expect, type Page } from "@playwright/test";

export interface AppOnlyRequests {
  /** onnxruntime-web's wasm was fetched, from the app itself, as wasm. */
  expectWasmFromApp(): void;
  /** No request left the app's origin. */
  expectNothingForeign(): void;
}

/** Watch `page`'s requests from now on (`baseURL`: the app's). */
export function watchAppOnly(page: Page, baseURL: string | undefined): AppOnlyRequests {
  const origin = new URL(baseURL ?? "").origin;
  const foreign: string[] = [];
  const wasm: { url: string; status: number; type: string | undefined }[] = [];
  page.on("request", (r) => {
    if (!r.url().startsWith(origin) && !r.url().startsWith("data:")) foreign.push(r.url());
  });
  page.on("response", (r) => {
    if (new URL(r.url()).pathname.endsWith(".wasm")) {
      wasm.push({ url: r.url(), status: r.status(), type: r.headers()["content-type"] });
    }
  });
  return {
    expectWasmFromApp() {
      expect(wasm.length).toBeGreaterThan(0);
      for (const w of wasm) {
        expect(w.url.startsWith(`${origin}/assets/`), w.url).toBe(true);
        expect(w.status).toBe(200);
        expect(w.type).toBe("application/wasm");
      }
    },
    expectNothingForeign() {
      expect(foreign).toEqual([]);
    },
  };
}
