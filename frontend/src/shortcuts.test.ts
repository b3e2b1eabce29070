// Key names: what a registration says and what a key press gives must meet.
import { describe, expect, it } from "vitest";
import {
  eventKeys,
  handleShortcutKey,
  listShortcuts,
  normalizeKeys,
  registerShortcut,
  type ShortcutSpec,
} from "./shortcuts";

const press = (key: string, mods: { ctrl?: boolean; shift?: boolean; alt?: boolean } = {}) => ({
  key,
  ctrlKey: mods.ctrl ?? false,
  metaKey: false,
  altKey: mods.alt ?? false,
  shiftKey: mods.shift ?? false,
});

describe("key names", () => {
  it("orders modifiers and upper-cases letters", () => {
    expect(normalizeKeys("shift+ctrl+z")).toBe("Ctrl+Shift+Z");
    expect(normalizeKeys("Esc")).toBe("Escape");
    expect(normalizeKeys("Cmd+S")).toBe("Ctrl+S");
    expect(normalizeKeys("?")).toBe("?");
    expect(normalizeKeys("+")).toBe("+");
    expect(normalizeKeys("Ctrl++")).toBe("Ctrl++");
  });

  it("names key presses like registrations", () => {
    expect(eventKeys(press("z", { ctrl: true }))).toBe("Ctrl+Z");
    expect(eventKeys(press("Z", { ctrl: true, shift: true }))).toBe("Ctrl+Shift+Z");
    expect(eventKeys(press("A", { shift: true }))).toBe("Shift+A");
    expect(eventKeys(press("a"))).toBe("A");
    // "?" needs Shift on most layouts; the symbol says it already.
    expect(eventKeys(press("?", { shift: true }))).toBe("?");
    expect(eventKeys(press("Delete"))).toBe("Delete");
    expect(eventKeys(press("Tab", { shift: true }))).toBe("Shift+Tab");
    expect(eventKeys(press(" "))).toBe("Space");
  });
});

/** Register a key that does nothing unless `more` says otherwise. */
const key = (keys: string, description: string, scope: string, more: Partial<ShortcutSpec> = {}) =>
  registerShortcut({ keys, description, scope, run: () => {}, ...more });

describe("registry", () => {
  it("lists what is registered until it is removed", () => {
    const before = listShortcuts().length;
    const remove = registerShortcut({
      keys: ["shift+a", "Enter"],
      description: "Accept all",
      scope: "Test",
      run: () => {},
    });
    const listed = listShortcuts().at(-1);
    expect(listed).toEqual({
      keys: ["Shift+A", "Enter"],
      description: "Accept all",
      scope: "Test",
      enabled: true,
    });
    remove();
    expect(listShortcuts()).toHaveLength(before);
  });

  it("says which keys are off now (the help overlay greys them)", () => {
    let editable = false;
    const remove = key("F", "Floor", "Test", { enabled: () => editable });
    expect(listShortcuts().at(-1)?.enabled).toBe(false);
    editable = true;
    expect(listShortcuts().at(-1)?.enabled).toBe(true);
    remove();
  });

  it("lists one of two registrations of a key in a scope: the one a press runs, if any", () => {
    let submitting = false;
    let accepting = false;
    const removers = [
      key("Shift+Enter", "Submit", "Flow", { enabled: () => submitting }),
      key("Shift+Enter", "Accept", "Flow", { enabled: () => accepting }),
      // Another scope's key of the same name is its own row.
      key("Shift+Enter", "Other", "Else"),
    ];
    const rows = () =>
      listShortcuts()
        .filter((s) => s.keys[0] === "Shift+Enter")
        .map((s) => `${s.description}:${s.enabled}`);
    expect(rows()).toEqual(["Submit:false", "Accept:false", "Other:true"]);
    accepting = true;
    expect(rows()).toEqual(["Accept:true", "Other:true"]);
    submitting = true;
    expect(rows()).toEqual(["Accept:true", "Other:true"]);
    accepting = false;
    expect(rows()).toEqual(["Submit:true", "Other:true"]);
    for (const remove of removers) remove();
  });

  it("says why when a key that is off is pressed, unless another registration takes it", () => {
    const said: string[] = [];
    let other = false;
    const removers = [
      key("Shift+K", "Knife", "Test", {
        run: () => said.push("ran"),
        enabled: () => false,
        whenOff: () => said.push("read only"),
      }),
      key("Shift+K", "Other", "Else", { run: () => said.push("other ran"), enabled: () => other }),
    ];
    const keyDown = () =>
      handleShortcutKey({
        ...press("K", { shift: true }),
        target: null,
        isComposing: false,
        defaultPrevented: false,
        preventDefault: () => {},
      } as unknown as KeyboardEvent);
    keyDown();
    expect(said).toEqual(["read only"]);
    other = true;
    keyDown();
    expect(said).toEqual(["read only", "other ran"]);
    for (const remove of removers) remove();
  });

  it("leaves out keys that are never this person's", () => {
    let reviewer = false;
    const remove = key("Shift+X", "Reject", "Test", { listed: () => reviewer });
    expect(listShortcuts().some((s) => s.description === "Reject")).toBe(false);
    reviewer = true;
    expect(listShortcuts().some((s) => s.description === "Reject")).toBe(true);
    remove();
  });
});
