"""The animations the kernel plays, in one table for the whole engine.

Rows are added as bodies' sequences bring new animations (an event may start a motion no body has
played yet); the arrays (:func:`acphys.fast.kernels.sequence.animation_table`) are made again
when the table has grown.
"""

from __future__ import annotations

import numpy as np

from acphys.fast.kernels.sequence import animation_table, load_sequence, store_sequences
from acphys.motion.animation import Animation
from acphys.motion.sequence import Sequence


class AnimationTable:
    """The engine's animations: ``anims``, ``pos_frames`` and ``hooks`` for the kernel."""

    def __init__(self) -> None:
        self.animations: list[Animation] = []
        self._index: dict[int, int] = {}
        self.anims, self.pos_frames, self.hooks = animation_table([])

    def _add(self, sequence: Sequence) -> None:
        grown = False
        for node in sequence.anim_list:
            animation = node.animation
            if animation is not None and id(animation) not in self._index:
                self._index[id(animation)] = len(self.animations)
                self.animations.append(animation)
                grown = True
        if grown:
            self.anims, self.pos_frames, self.hooks = animation_table(self.animations)

    def load(self, record: np.void, sequence: Sequence) -> bool:
        """Copy ``sequence`` into ``record`` (adding its animations); False if the kernel cannot play it."""
        self._add(sequence)
        return load_sequence(record, sequence, self._index)

    def store(self, records: np.ndarray, sequences: list[Sequence | None]) -> None:
        """Copy each record's sequence back into its sequence (None: a body without one)."""
        store_sequences(records, sequences, self.animations)
