// Test fixture (unit tests only): a support relation, by default the pipeline's guess.
import type { SupportRelation } from "@holiscene/schema";

export const supportRelation = (
  child: string,
  parent: string,
  extra: Partial<SupportRelation> = {},
): SupportRelation => ({
  child,
  parent,
  type: "below",
  source: "auto",
  confidence: 0.7,
  author: null,
  time: null,
  ...extra,
});
