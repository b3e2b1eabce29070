"""Scenes, their revisions and pipeline jobs, in the database and the data directory."""
