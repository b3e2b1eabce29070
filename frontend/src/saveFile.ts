// Hand a file made in the page (a blob) to the browser's downloads.

/** Download `blob` as `fileName`, as a click on a link with `download` would. */
export function saveBlob(blob: Blob, fileName: string): void {
  const url = URL.createObjectURL(blob);
  const link = document.createElement("a");
  link.href = url;
  link.download = fileName;
  document.body.append(link);
  link.click();
  link.remove();
  // Revoked later: the download may read the URL after click() returns.
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
