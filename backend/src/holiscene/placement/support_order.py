"""Orders that follow the support graph."""

from __future__ import annotations

from holiscene_schema import SceneObject, SupportRelation


def supporters_first(
    objects: list[SceneObject], support_of: dict[str, SupportRelation]
) -> list[SceneObject]:
    """Objects ordered so that every supporter comes before what it supports."""

    def depth(obj_id: str) -> int:
        steps = 0
        while obj_id in support_of and steps <= len(objects):
            obj_id = support_of[obj_id].parent
            steps += 1
        return steps

    return sorted(objects, key=lambda o: depth(o.id))
