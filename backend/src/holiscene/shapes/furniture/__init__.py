"""Parametric builders grouped by family; each is `(ShapeBuilder, Generator) -> None`."""
