"""Hand-written priors about indoor scenes (until learned ones replace them)."""
