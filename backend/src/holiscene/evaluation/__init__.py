"""Measuring predictions against ground truth with the thesis's metrics."""
