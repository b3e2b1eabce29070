// The scene list's "Import a dataset" card: a zip given to it, imported without running the
// pipeline, and the card's summary once the import has finished.
import { expect, type Page } from "@playwright/test";

type ZipFile = string | { name: string; mimeType: string; buffer: Buffer };

export async function importZip(page: Page, zip: ZipFile): Promise<void> {
  await page.getByTestId("dataset-import-file").setInputFiles(zip);
  await page.getByTestId("dataset-import-pipeline").uncheck();
  await page.getByTestId("dataset-import-submit").click();
  await expect(page.getByTestId("dataset-import-summary")).toBeVisible({ timeout: 60_000 });
}
