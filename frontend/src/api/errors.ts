// Errors of the HTTP API, with the server's `detail` turned into a readable message.

/** A non-2xx answer of the API. */
export class ApiError extends Error {
  readonly status: number;
  readonly detail: unknown;

  constructor(status: number, detail: unknown, fallback: string) {
    super(describeDetail(detail) ?? fallback);
    this.name = "ApiError";
    this.status = status;
    this.detail = detail;
  }
}

/** 409 on an edit: the revision the edit was based on is no longer the latest. */
export class ConflictError extends ApiError {
  readonly currentRevision: number | null;

  constructor(detail: unknown) {
    super(409, detail, "The scene was changed by someone else.");
    this.name = "ConflictError";
    this.currentRevision = readCurrentRevision(detail);
  }
}

function readCurrentRevision(detail: unknown): number | null {
  if (detail && typeof detail === "object" && "current_revision" in detail) {
    const value = (detail as { current_revision: unknown }).current_revision;
    if (typeof value === "number") return value;
  }
  return null;
}

/**
 * The server's error detail as text: a string, `{message}`, or FastAPI's list of validation
 * errors (`[{loc, msg}]`).
 */
export function describeDetail(detail: unknown): string | null {
  if (typeof detail === "string") return detail;
  if (Array.isArray(detail)) {
    const parts = detail.map((item) => {
      if (item && typeof item === "object" && "msg" in item) {
        const { loc, msg } = item as { loc?: unknown; msg: unknown };
        const where = Array.isArray(loc) ? loc.filter((p) => p !== "body").join(".") : "";
        return where ? `${where}: ${String(msg)}` : String(msg);
      }
      return JSON.stringify(item);
    });
    return parts.join("; ");
  }
  if (detail && typeof detail === "object" && "message" in detail) {
    return String((detail as { message: unknown }).message);
  }
  return null;
}

/**
 * What went wrong, for a person: the API's message, or, when no answer came at all (the
 * browser's "Failed to fetch"), that the server could not be reached.
 */
export function errorText(error: unknown): string {
  if (error instanceof TypeError && /fetch|network|load failed/i.test(error.message)) {
    return "the server could not be reached (is it running? your changes are kept)";
  }
  return error instanceof Error ? error.message : String(error);
}
