"""Retail's pooled transition: what one sweep leaves to the next (issue 14).

Retail sweeps with a transition from a static pool whose fields outlive a sweep
(``CTransition::makeTransition``; ``CTransition::init`` @ 0x00509DD0, acclient.c:311595, resets
some of them). The kernel's transition record keeps the fields a later sweep may read before it
sets them in its first ``layout.CARRIED`` bytes, and an update handed back to the reference path
restores only those: every other field is set afresh by the next sweep, the kernel's or the
reference path's, before it is read. Here that is put to the test: those fields are poisoned with
what the same world's transition held long before (plausible values, wrong ones) before every
kernel call and every update on the reference path, and the traces must not change.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from acphys.bench import WORKLOADS
from acphys.fast import engine as engine_module
from acphys.fast.differential import same_run
from acphys.fast.layout import CARRIED, TRANSITION
from acphys.simulation import Simulation


def test_the_carried_fields_come_first_and_the_sweeps_own_after() -> None:
    names = TRANSITION.names
    first_own = names.index("oi_state")
    assert TRANSITION.fields["oi_state"][1] == CARRIED
    carried = set(names[:first_own])
    # retail's values that outlive COLLISIONINFO::init (acclient.c:311566): the planes and normals
    # (only their valid flags are reset), and the step-down's numbers
    assert {"contact_n", "contact_d", "last_known_contact_n", "sliding_normal", "collision_normal"} <= carried
    assert {"walk_interp", "step_down_amt", "memo_valid", "memo_cells"} <= carried
    # what init and the sweep's set-up write before anything reads them
    assert not {"contact_plane_valid", "curr_origin", "check_origin", "oi_state", "num_cells"} & carried


def _run(load: Callable[[], Simulation], path: Path) -> Simulation:
    sim = load()
    sim.run(trace=path)
    return sim


def _planes(sim: Simulation) -> list[str]:
    """Every body's contact plane as its object holds it at the end, valid or not (a trace shows
    it only in contact)."""
    sim.sync()
    return [repr((*body.contact_plane.N, body.contact_plane.d)) for body in sim.bodies]


def _poison(monkeypatch: pytest.MonkeyPatch, start: int = CARRIED) -> list[int]:
    """Before every kernel call and every reference update, overwrite the transition's fields from
    byte ``start`` on: every number with NaN (which no trace would hide), every index and flag with
    what it held at the second kernel call (a cell, a body, a state of this world, but long gone).
    Returns the count of poisonings (kernel calls, reference updates)."""
    kernels = engine_module.kernels
    run_bodies = kernels.run_bodies
    reference_update = engine_module.FastPhysics._reference_update
    kept: list[np.ndarray] = []
    counts = [0, 0]

    def poison(tr_array: np.ndarray) -> None:
        if len(kept) < 2:  # the first tick's transition is the scenario's start: keep the next
            kept.append(tr_array.copy())
            if len(kept) == 2:
                for name in TRANSITION.names:
                    if TRANSITION.fields[name][0].base == np.float64:
                        kept[1][name] = np.nan
            return
        raw = tr_array.view(np.uint8)
        raw[start:] = kept[1].view(np.uint8)[start:]

    def poisoned_run(context, tr_array, *rest):
        poison(tr_array)
        counts[0] += 1
        return run_bodies(context, tr_array, *rest)

    def poisoned_update(self, i):
        poison(self._transition)
        counts[1] += 1
        return reference_update(self, i)

    monkeypatch.setattr(kernels, "run_bodies", poisoned_run)
    monkeypatch.setattr(engine_module.FastPhysics, "_reference_update", poisoned_update)
    return counts


@pytest.mark.parametrize("workload", ["mixed", "hills", "crowd", "fallers"])
def test_a_sweep_reads_nothing_of_the_last_but_the_carried_fields(
    workload: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The bench's small populations run twice on the fast engine, the second time poisoned (the
    mixed landblock's 100 bodies for 4 s: updates that sweep into its house are handed back to
    the reference path mid-sweep, the transition left as the kernel's sweep left it)."""
    build = WORKLOADS[workload][1]
    bodies, seconds = (100, 4.0) if workload == "mixed" else (24, 2.0)
    clean = _run(lambda: build(bodies, seconds, "fast"), tmp_path / "clean.jsonl")
    counts = _poison(monkeypatch)
    poisoned = _run(lambda: build(bodies, seconds, "fast"), tmp_path / "poisoned.jsonl")
    assert counts[0] > 50
    assert same_run(tmp_path / "clean.jsonl", tmp_path / "poisoned.jsonl")
    assert _planes(poisoned) == _planes(clean)
    assert poisoned.physics.counts.kernel == clean.physics.counts.kernel > 0
    if workload == "mixed":  # the reference path swept from a poisoned pool too
        assert counts[1] > 0 and poisoned.physics.counts.reference > 0


def test_the_poison_shows_where_a_carried_field_is_read(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The test above can fail: balls in flight sweep without a contact plane and keep the one the
    last sweep left (``CPhysicsObj::SetPositionInternal`` @ 0x00515330, acclient.c:322503, copies
    the transition's plane, valid or not): poisoned from the first byte on, a ball thrown up
    holds a NaN plane when the run ends in its flight."""
    build = WORKLOADS["fallers"][1]
    clean = _run(lambda: build(24, 0.5, "fast"), tmp_path / "clean.jsonl")
    _poison(monkeypatch, start=0)
    poisoned = _run(lambda: build(24, 0.5, "fast"), tmp_path / "poisoned.jsonl")
    assert any("nan" in plane for plane in _planes(poisoned))
    assert not any("nan" in plane for plane in _planes(clean))
