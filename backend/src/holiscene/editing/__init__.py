"""People's changes to a scene, with no database and no HTTP: the edits (supports, objects,
room layout) applied to a scene document, and the annotation workflow's rules (who may
change a scene's state, and when)."""
