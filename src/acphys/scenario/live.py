"""Bodies and events added to a simulation that is already built, read as a scenario reads them.

``Simulation.add_body({...})`` takes the keys of a ``[[body]]`` table and ``Simulation.add_event(at,
body, action, **keys)`` those of an ``[[event]]``: both are checked exactly as in a scenario file
(the same readers, the same limits, a :class:`~acphys.scenario.values.ScenarioError` naming the
key). What they may name is what the simulation's scenario declared: its ``[setup.NAME]`` and
``[motion_table.NAME]`` tables, its ``[script.NAME]`` ids and its ``[data]`` DAT files (opened
again for the call), besides the built-in setups and motion tables. A simulation made directly
(``Simulation(world, ...)``) knows only the built-in ones.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from acphys.scenario import values as read
from acphys.scenario.events import read_event
from acphys.scenario.values import Ctx, ScenarioError

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj
    from acphys.scenario import Tables
    from acphys.setup import Setup
    from acphys.simulation import Event
    from acphys.world.world import World


class ScenarioParts:
    """What a simulation keeps of its scenario to read more bodies and events as the file would:
    ``setups`` (its ``[setup.NAME]``), ``tables`` (its motion tables, the built-in ones it made
    included, so new bodies share them), ``scripts`` (``[script.NAME]`` ids), and its ``[data]``
    table with the ``folder`` its relative paths resolve against."""

    def __init__(
        self,
        setups: dict[str, Setup] | None = None,
        tables: Tables | None = None,
        scripts: dict[str, int] | None = None,
        data: Mapping[str, Any] | None = None,
        folder: str | Path | None = None,
    ) -> None:
        from acphys.scenario import Tables

        self.setups = setups if setups is not None else {}
        self.tables = tables if tables is not None else Tables({})
        self.scripts = scripts if scripts is not None else {}
        self.data = dict(data) if isinstance(data, Mapping) else {}
        self.folder = folder

    def read_body(
        self, world: World, keys: Mapping[str, Any], source: str = "add_body"
    ) -> tuple[PhysicsObj, list[str]]:
        """A body made in ``world`` from the keys of a ``[[body]]`` table, placed as the scenario
        reader places one (``on_ground`` included), and the warnings its reading gave. On an
        error (a ScenarioError naming the key) nothing of the body is left in the world."""
        from acphys.scenario import _motion_table, _read_body, _setup_lookup
        from acphys.scenario.retail_data import read_data

        ctx = Ctx(source)
        table = dict(keys) if isinstance(keys, Mapping) else keys
        # The id the body will have, so that one a later key refuses can be taken out again.
        object_id = None
        if isinstance(table, dict) and "id" not in table:
            object_id = world.next_object_id()
            table["id"] = object_id
        elif isinstance(table, dict):
            try:
                object_id = read.object_id(Ctx(source), "body.id", table["id"])
            except ScenarioError:  # _read_body reports it, before it makes anything
                object_id = None
            if object_id is not None and world.get_object(object_id) is not None:
                object_id = None  # taken: _read_body refuses it before it makes anything
        with read_data(ctx, self.data, self.folder) as data:
            find_setup = _setup_lookup(ctx, self.setups, data, self.tables)

            def find_table(key: str, value: Any) -> Any:
                return _motion_table(ctx, key, value, self.tables, data)

            try:
                body = _read_body(ctx, "body", table, world, find_setup, find_table)
            except BaseException:
                made = world.get_object(object_id) if object_id is not None else None
                if made is not None:
                    world.remove_object(made)
                raise
        return body, list(ctx.warnings)

    def read_event(
        self, at: float, body: str, action: str, keys: Mapping[str, Any], bodies: dict[str, PhysicsObj]
    ) -> Event:
        """An event from the keys of an ``[[event]]`` table (``at``, ``body``, ``action`` and the
        action's own), checked against ``bodies`` and the scenario's scripts."""
        raw = {"at": at, "body": body, "action": action, **keys}
        return read_event(Ctx("add_event"), "event", raw, bodies, math.inf, self.scripts)


__all__ = ["ScenarioParts"]
