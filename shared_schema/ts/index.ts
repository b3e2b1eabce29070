export type * from "./contract";
export * from "./vocabulary";
