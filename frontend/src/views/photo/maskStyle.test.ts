// The mask style: by object and 0.42 at first, remembered, out-of-range or broken values
// fall back, listeners hear every change.
import { describe, expect, it } from "vitest";
import { MemoryStorage } from "../../testing/memoryStorage";
import { DEFAULT_MASK_STYLE, MaskStyleSetting } from "./maskStyle";

describe("mask style", () => {
  it("starts coloured by object and remembers changes in storage", () => {
    const storage = new MemoryStorage();
    const setting = new MaskStyleSetting(storage);
    expect(setting.get()).toEqual(DEFAULT_MASK_STYLE);
    expect(setting.get().colouring).toBe("object");
    setting.set({ colouring: "class" });
    setting.set({ opacity: 0.8 });
    expect(new MaskStyleSetting(storage).get()).toEqual({ colouring: "class", opacity: 0.8 });
  });

  it("keeps the opacity in range and ignores what it cannot read", () => {
    const storage = new MemoryStorage();
    const setting = new MaskStyleSetting(storage);
    setting.set({ opacity: 7 });
    expect(setting.get().opacity).toBe(1);
    setting.set({ opacity: -1 });
    expect(setting.get().opacity).toBe(0.05);
    storage.setItem("holiscene.maskStyle", "{not json");
    expect(new MaskStyleSetting(storage).get()).toEqual(DEFAULT_MASK_STYLE);
  });

  it("tells its listeners, until they unsubscribe", () => {
    const setting = new MaskStyleSetting(new MemoryStorage());
    const heard: string[] = [];
    const stop = setting.subscribe((style) => heard.push(style.colouring));
    setting.set({ colouring: "class" });
    stop();
    setting.set({ colouring: "object" });
    expect(heard).toEqual(["class"]);
  });
});
