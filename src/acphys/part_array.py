"""``CPartArray``: the body's parts, setup and animation sequence, as the tick sees them."""

from __future__ import annotations

from acphys.attachments import MotionTableManager
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.motion.sequence import Sequence
from acphys.setup import Setup


class PartArray:
    """Retail ``CPartArray`` (acclient.h:30762): owns the setup and the sequence."""

    __slots__ = ("motion_table_manager", "sequence", "setup")

    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.sequence = Sequence()
        self.motion_table_manager: MotionTableManager | None = None

    def update(self, quantum: float, offset_frame: Frame) -> None:
        """Advance the sequence, writing root motion into ``offset_frame``.

        Retail: CPartArray::Update @ 0x00517DB0 (acclient.c:325139)
        """
        self.sequence.update(quantum, offset_frame)

    def get_num_sphere(self) -> int:
        """Retail: CPartArray::GetNumSphere @ 0x00518060 (acclient.c:325357)"""
        return len(self.setup.spheres)

    def get_sphere(self) -> list[Sphere]:
        """Retail: CPartArray::GetSphere @ 0x00518070 (acclient.c:325363)"""
        return self.setup.spheres

    def handle_movement(self) -> None:
        """Tick the motion table manager, if there is one.

        Retail: CPartArray::HandleMovement @ 0x00517D60 (acclient.c:325105)
        """
        if self.motion_table_manager is not None:
            self.motion_table_manager.use_time()
