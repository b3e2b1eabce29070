"""Settings and the database connection."""
