"""Free class names resolved by their words, for the names no table lists as they are.

SUN RGB-D's annotators typed their class names freely (about 6000 raw names: "chairs",
"office chair", "book shelf", "chair 2", "pillow(s)", "chiar"). After the vocabulary's exact
lookup fails (classes.py), a name is read as English words (lower case, anything but letters
a space, a part in parentheses left out: "chair (broken)") and resolved, in this order:

1. the words as they are or singular, joined by `_` ("book shelves" -> book_shelf) or with
   nothing ("coffee table" -> coffeetable, the form of `coffee_table` without its `_`);
2. "X of Y": X ("chest of drawers" is whole in step 1); Y when X is generic ("pile of
   books" -> books); "X on Y" (in, with, for, ...: the prepositions below): X ("books on
   shelf" -> books, "lamp with shade" -> lamp);
3. the head noun: the longest known tail of the words ("small kitchen cabinet" ->
   kitchen_cabinet; "office chair" -> chair); a generic head ("frame", "top", "unit",
   "stack") names a part or a heap of what its modifiers name, so they decide first ("bed
   frame" -> bed, "table top" -> table, "book stack" -> books; "frame" alone is a picture);
4. a typo in the last word (or in its singular): one pair of neighbouring letters swapped
   ("chiar"), one letter missing ("pilow", "bookself") or, in a long word, one too many
   ("cabinent"), when every known word that fixes it has one class. A letter typed for
   another is not fixed: too many real words are one letter from a class ("cable", "table").

A word that modifies a known head never overrides it ("tv remote" is a remote, a prop), so
names whose head says the wrong thing are listed whole in the alias table ("toilet seat").
frontend/src/state/classWords.ts is the same in TypeScript, pinned by
shared_schema/vectors/class_names.json; the word lists below reach it through
vocabulary.json.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable

# Head nouns that name a part, a unit or a heap of the thing their modifiers name.
GENERIC_HEADS: tuple[str, ...] = (
    "frame", "top", "base", "leg", "unit", "set", "piece", "part", "item", "object", "thing",
    "stack", "pile", "heap", "bunch", "collection", "group", "row", "pair", "lot", "area",
    "section", "surface", "side", "corner", "edge",
)  # fmt: skip

# Words after which a name says where or with what the thing is: the head comes before.
PREPOSITIONS: tuple[str, ...] = (
    "on", "in", "with", "for", "under", "near", "at", "from", "by", "behind", "over",
    "against", "beside", "inside", "above", "below",
)  # fmt: skip

# Plurals the spelling rules in `singular` get wrong.
IRREGULAR_PLURALS: dict[str, str] = {
    "people": "person", "persons": "person", "men": "man", "women": "woman",
    "children": "child", "feet": "foot", "teeth": "tooth", "mice": "mouse",
    "knives": "knife", "leaves": "leaf", "halves": "half", "shelves": "shelf",
}  # fmt: skip

# Typo fixes: only on words this long (shorter ones are too often another real word), and
# adding a letter back only into one at least as long as SHORTEST_TYPO; taking one out only
# of one at least LONGEST_TYPO long ("tablet" is a word, not "table" mistyped).
SHORTEST_TYPO = 5
LONGEST_TYPO = 7

Lookup = Callable[[str], str | None]  # a key (words joined by "_") -> its class, or None


def class_words(name: str) -> list[str]:
    """The name's words: lower case, a part in parentheses left out, every run of characters
    other than a-z a break (digits, punctuation, dashes and underscores)."""
    return re.findall(r"[a-z]+", re.sub(r"\([^()]*\)", " ", name.lower()))


def singular(word: str) -> str:
    """The word's singular by English spelling rules: chairs, couches, boxes, glasses,
    batteries, shelves; a word that is not a plural is left as it is (glass, bus)."""
    if word in IRREGULAR_PLURALS:
        return IRREGULAR_PLURALS[word]
    if len(word) <= 2 or word.endswith(("ss", "us", "is")) or not word.endswith("s"):
        return word
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith("lves"):
        return word[:-3] + "f"
    if word.endswith(("ches", "shes", "xes", "sses", "zes")):
        return word[:-2]
    return word[:-1]


def resolve_words(words: list[str], lookup: Lookup, known_words: Iterable[str]) -> str | None:
    """The class of a name's words (steps 1-4 above), or None. `lookup` knows the
    vocabulary's keys (classes, aliases, and aliases with their `_` left out); `known_words`
    are its one-word keys, the words a typo may be fixed to."""
    if not words:
        return None
    found = _phrase(words, lookup) or _by_head(words, lookup)
    if found is not None:
        return found
    last = words[-1]
    fixes = {w for form in {last, singular(last)} for w in typo_fixes(form, known_words)}
    fixed = {c for w in fixes if (c := lookup(w)) is not None}
    if len(fixed) == 1:
        return next(iter(fixed))
    return None


def _phrase(words: list[str], lookup: Lookup) -> str | None:
    """Step 1: the words as one key."""
    singulars = [singular(w) for w in words]
    for form in (words, singulars):
        for joiner in ("_", ""):
            found = lookup(joiner.join(form))
            if found is not None:
                return found
    return None


def _by_head(words: list[str], lookup: Lookup) -> str | None:
    """Steps 2 and 3: "X of Y" and "X on Y", then the longest known tail, a generic head
    after its modifiers."""
    at = next((i for i, w in enumerate(words) if i > 0 and w in ("of", *PREPOSITIONS)), None)
    if at is not None:
        head, rest = words[:at], words[at + 1 :]
        if words[at] == "of" and singular(head[-1]) in GENERIC_HEADS:
            return _resolve(rest, lookup) or _resolve(head, lookup)
        return _resolve(head, lookup)
    if singular(words[-1]) in GENERIC_HEADS and len(words) > 1:
        found = _resolve(words[:-1], lookup)
        if found is not None:
            return found
    for start in range(1, len(words)):
        found = _phrase(words[start:], lookup)
        if found is not None:
            return found
    return None


def _resolve(words: list[str], lookup: Lookup) -> str | None:
    return _phrase(words, lookup) or _by_head(words, lookup) if words else None


def typo_fixes(word: str, known_words: Iterable[str]) -> list[str]:
    """The known words one typo away from `word` (see the module's step 4), sorted."""
    if len(word) < SHORTEST_TYPO:
        return []
    known = set(known_words)
    near: set[str] = set()
    for i in range(len(word) - 1):  # neighbours swapped
        near.add(word[:i] + word[i + 1] + word[i] + word[i + 2 :])
    if len(word) >= LONGEST_TYPO:  # one letter too many
        near.update(word[:i] + word[i + 1 :] for i in range(len(word)))
    # one letter missing: a known word that gives `word` with one of its letters taken out
    near.update(k for k in known if len(k) == len(word) + 1 and _one_out(k, word))
    return sorted(w for w in near if w in known and w != word)


def _one_out(longer: str, shorter: str) -> bool:
    return any(longer[:i] + longer[i + 1 :] == shorter for i in range(len(longer)))
