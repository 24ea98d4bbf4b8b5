"""Animation root motion and motion: sequences (and, with later issues, motion tables and interpreters)."""

from acphys.motion.sequence import Sequence

__all__ = ["Sequence"]
