"""Data shipped with acphys: built-in scenarios."""
