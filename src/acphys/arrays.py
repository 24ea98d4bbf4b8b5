"""Many bodies' state as NumPy arrays: what :meth:`acphys.Simulation.arrays` hands out.

One row per body, in the order given (the simulation's: :attr:`~acphys.Simulation.bodies`, the
order they were added). Every value is a copy: changing an array changes no body.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from acphys.constants import BLOCK_LENGTH

if TYPE_CHECKING:  # NumPy is imported on first use: ``import acphys`` does not load it
    import numpy as np

    from acphys.physics_obj import PhysicsObj

#: Values per body in the table :func:`body_arrays` builds: cell id, origin, quaternion,
#: velocity, cached velocity, omega, transient state.
_COLUMNS = 1 + 3 + 4 + 3 + 3 + 3 + 1


@dataclass(frozen=True)
class BodyArrays:
    """Bodies' state after the last step, row ``i`` for ``names[i]``.

    Lengths in metres, velocities in m/s, ``omegas`` in radians per second (as traces write
    them). ``origins`` are landblock-local (in the landblock of ``cell_ids``, as
    ``body.position.frame.origin``); ``positions`` are the same points in one frame for the whole
    map, landblock ``0xXXYY`` starting at (XX·192, YY·192) m, so rows of bodies in different
    landblocks compare (and ``acphys plot`` draws paths in the same frame).
    """

    #: The bodies' names, in row order.
    names: tuple[str, ...]
    #: ``position.objcell_id``, shape (N,), uint32.
    cell_ids: np.ndarray
    #: ``position.frame.origin``, landblock-local, shape (N, 3).
    origins: np.ndarray
    #: The origins in the map-wide frame, shape (N, 3).
    positions: np.ndarray
    #: The frames' quaternions ``(w, x, y, z)``, shape (N, 4).
    orientations: np.ndarray
    #: ``velocity`` (``m_velocityVector``), shape (N, 3).
    velocities: np.ndarray
    #: ``cached_velocity``: the displacement of the last step over its quantum, shape (N, 3).
    cached_velocities: np.ndarray
    #: ``omega``, shape (N, 3).
    omegas: np.ndarray
    #: ``transient_state`` bits (:class:`~acphys.flags.TransientState`), shape (N,), uint32.
    transient_states: np.ndarray

    @classmethod
    def of_columns(
        cls,
        names: tuple[str, ...],
        cell_ids: np.ndarray,
        origins: np.ndarray,
        orientations: np.ndarray,
        velocities: np.ndarray,
        cached_velocities: np.ndarray,
        omegas: np.ndarray,
        transient_states: np.ndarray,
    ) -> BodyArrays:
        """The arrays from their columns (owned by the result), the map-wide ``positions`` made
        from ``cell_ids`` and ``origins``."""
        import numpy as np

        cell_ids = cell_ids.astype(np.uint32)
        blocks = cell_ids >> 16
        positions = origins.copy()
        positions[:, 0] = (blocks >> 8).astype(np.float64) * BLOCK_LENGTH + origins[:, 0]
        positions[:, 1] = (blocks & 0xFF).astype(np.float64) * BLOCK_LENGTH + origins[:, 1]
        return cls(
            names=names,
            cell_ids=cell_ids,
            origins=origins,
            positions=positions,
            orientations=orientations,
            velocities=velocities,
            cached_velocities=cached_velocities,
            omegas=omegas,
            transient_states=transient_states.astype(np.uint32),
        )

    def __len__(self) -> int:
        return len(self.names)

    def index(self, name: str) -> int:
        """The row of the body called ``name`` (a ValueError when there is none)."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ValueError(f"no body named {name!r} in these arrays") from None


def body_arrays(bodies: Iterable[PhysicsObj]) -> BodyArrays:
    """The state of ``bodies`` as :class:`BodyArrays` (float64 arrays: every value is exact)."""
    import numpy as np

    names = []
    rows = []
    for body in bodies:
        names.append(body.name)
        cell_id = body.position.objcell_id
        frame = body.position.frame
        o, v, c, w = frame.origin, body.velocity, body.cached_velocity, body.omega
        rows.append(
            (
                cell_id,
                o.x,
                o.y,
                o.z,
                frame.qw,
                frame.qx,
                frame.qy,
                frame.qz,
                v.x,
                v.y,
                v.z,
                c.x,
                c.y,
                c.z,
                w.x,
                w.y,
                w.z,
                body._transient_state,
            )
        )
    table = np.array(rows, dtype=np.float64).reshape(len(rows), _COLUMNS)
    return BodyArrays.of_columns(
        names=tuple(names),
        cell_ids=table[:, 0],
        origins=table[:, 1:4].copy(),
        orientations=table[:, 4:8].copy(),
        velocities=table[:, 8:11].copy(),
        cached_velocities=table[:, 11:14].copy(),
        omegas=table[:, 14:17].copy(),
        transient_states=table[:, 17],
    )


__all__ = ["BodyArrays", "body_arrays"]
