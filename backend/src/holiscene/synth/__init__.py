"""Synthetic indoor scenes with exact ground truth: plan a room, render it, write it out."""
