"""Likeness figures of a texture against its exemplar."""
