"""``[script.NAME]``: physics scripts, timed lists of hooks a scenario can play on a body.

A script is ``hooks = [{ at = SECONDS, kind = "...", ... }, ...]`` with the
hook kinds and arguments of animation hooks. Retail loads scripts from the
DAT by id; a scenario's scripts are registered under fresh ids
(``register_script``) and its ``play_script`` events name them.
"""

from __future__ import annotations

import itertools
from typing import Any

from acphys.managers.scripts import PhysicsScript, PhysicsScriptData, register_script
from acphys.scenario import values as read
from acphys.scenario.motion_tables import HOOK_KEYS, read_hook
from acphys.scenario.values import Ctx

#: Scenario scripts get ids in the physics-script DID range, fresh for every scenario read.
_SCRIPT_IDS = itertools.count(0x33F00001)


def read_scripts(ctx: Ctx, raw: Any) -> dict[str, int]:
    """Register every ``[script.NAME]`` and return the id each name got (a script with a problem
    is reported and left out)."""
    if not isinstance(raw, dict):
        raise ctx.fail("script", f"expected tables [script.NAME], got {read.kind(raw)}")
    ids: dict[str, int] = {}
    for name, value in raw.items():
        with ctx.part(f"script.{name}"):
            ids[name] = _read_script(ctx, f"script.{name}", value)
    return ids


def _read_script(ctx: Ctx, key: str, value: Any) -> int:
    """One ``[script.NAME]``, registered; its id."""
    table = read.table(ctx, key, value, ("hooks",))
    entries = read.list_of_tables(ctx, f"{key}.hooks", table.get("hooks", []))
    if not entries:
        raise ctx.fail(f"{key}.hooks", "missing: a script needs at least one hook")
    data = []
    for index, item in enumerate(entries):
        where = f"{key}.hooks[{index}]"
        entry = read.table(ctx, where, item, ("at", *HOOK_KEYS))
        if "at" not in entry:
            raise ctx.fail(f"{where}.at", "missing (a script hook needs at and kind)")
        # PhysicsScriptData::start_time is a double (acclient.h:31994): not narrowed
        at = read.ranged(ctx, f"{where}.at", entry["at"], 0.0, 1e6)
        data.append(PhysicsScriptData(at, read_hook(ctx, where, entry, "at")))
    script_id = next(_SCRIPT_IDS)
    register_script(script_id, PhysicsScript(data))
    return script_id
