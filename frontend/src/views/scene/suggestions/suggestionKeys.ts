// The keys of object suggestions: detect, accept the selected box, accept all, reject.
import { registerShortcut } from "../../../shortcuts";
import {
  ACCEPT_ALL_KEY,
  ACCEPT_KEY,
  DETECT_KEY,
  type DetectorBarActions,
  REJECT_KEY,
} from "./detectorBar";

const SCOPE = "Object suggestions";

export interface SuggestionKeyInputs extends DetectorBarActions {
  /** Nothing is loading, running or being added. */
  idle(): boolean;
  /** There are boxes to act on. */
  hasOffers(): boolean;
  editable(): boolean;
}

/** Register the keys; returns the function that removes them. */
export function suggestionKeys(keys: SuggestionKeyInputs): () => void {
  const { idle, hasOffers, editable } = keys;
  const removers = [
    registerShortcut({
      keys: DETECT_KEY,
      description: "Detect objects in the photo (suggested boxes to accept or reject)",
      scope: SCOPE,
      run: keys.detect,
      enabled: idle,
    }),
    registerShortcut({
      keys: ACCEPT_KEY,
      description: "Accept the selected suggested box as an object",
      scope: SCOPE,
      run: keys.acceptSelected,
      enabled: () => hasOffers() && idle() && editable(),
    }),
    registerShortcut({
      keys: ACCEPT_ALL_KEY,
      description: "Accept every suggested box (guesses one by one)",
      scope: SCOPE,
      run: keys.acceptAll,
      enabled: () => hasOffers() && idle() && editable(),
    }),
    registerShortcut({
      keys: REJECT_KEY,
      description: "Reject the selected suggested box",
      scope: SCOPE,
      run: keys.rejectSelected,
      enabled: () => hasOffers() && idle() && editable(),
    }),
  ];
  return () => {
    for (const remove of removers) remove();
  };
}
