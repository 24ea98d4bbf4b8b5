"""Parents and children: CHILDLIST, set_parent / unset_parent, UpdateChildrenInternal.

A held object is carried by its parent's ``set_frame`` (acclient.c:321327, which ends in
UpdateChildrenInternal), is skipped by ``update_object`` (``if (this->parent || ...)``,
acclient.c:323080) and by other bodies' sweeps (``!v5->parent`` in
CObjCell::find_obj_collisions, acclient.c:347141), and follows its parent from cell to cell
(the children loops of enter_cell, acclient.c:318201, and leave_cell, 318243).

Headings are compass degrees: heading 90 faces +x, so it turns a body-local (x, y, z) into
(y, -x, z) in the world.
"""

from __future__ import annotations

import pytest

from acphys.body.children import WHOLE_OBJECT, ChildList
from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.geometry.bsp_builder import build_box_tree
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.setup import LocationType, Setup, SetupPart
from acphys.simulation import Physics
from support import place

PARENT_AT = (96.0, 96.0, 50.0)


def _steps(body) -> list[float]:
    seen: list[float] = []
    body.observer = lambda _body, quantum: seen.append(quantum)
    return seen


class TestChildList:
    """CHILDLIST::add_child @ 0x0051B270 (acclient.c:329035), remove_child @ 0x0051AF90 (328819),
    FindChildIndex @ 0x0051B080 (328883)."""

    def test_entries_keep_their_order_and_a_copy_of_the_frame(self, world):
        a, b = place(world, name="a"), place(world, name="b")
        frame = Frame(V(1.0, 2.0, 3.0))
        children = ChildList()
        children.add_child(a, frame, 0, 7)
        children.add_child(b, frame, WHOLE_OBJECT, 0)
        frame.origin.x = 99.0
        assert children.objects == [a, b]
        assert children.frames[0].origin == V(1.0, 2.0, 3.0)
        assert children.part_numbers == [0, WHOLE_OBJECT]
        assert children.location_ids == [7, 0]
        assert children.find_child_index(b) == 1

    def test_removing_shifts_the_later_entries_down(self, world):
        a, b, c = (place(world, name=n) for n in "abc")
        children = ChildList()
        for index, obj in enumerate((a, b, c)):
            children.add_child(obj, Frame(V(float(index), 0.0, 0.0)), index, 0)
        children.remove_child(a)
        assert children.objects == [b, c]
        assert [f.origin.x for f in children.frames] == [1.0, 2.0]
        assert children.part_numbers == [1, 2]

    def test_removing_an_object_that_is_not_held_drops_the_last_entry(self, world):
        # The search stops at the count (acclient.c:328834-328842), the count drops by one (328844-328845)
        # and nothing is shifted: the last entry is gone.
        a, b, stranger = (place(world, name=n) for n in ("a", "b", "stranger"))
        children = ChildList()
        children.add_child(a, Frame(), 0, 0)
        children.add_child(b, Frame(), 0, 0)
        children.remove_child(stranger)
        assert children.objects == [a]
        assert children.find_child_index(b) is None


class TestSetParent:
    """CPhysicsObj::set_parent @ 0x00515B50 (acclient.c:323002) and add_child @ 0x0050F8F0 (316768)."""

    def test_the_child_is_put_at_the_parent_frame_combined_with_its_offset(self, world):
        parent = place(world, name="parent", origin=PARENT_AT, heading=90.0)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame.from_heading(V(0.25, 0.5, 1.0), 90.0))
        # Frame::combine (acclient.c:319448): origin = parent origin + R(90°)·(0.25, 0.5, 1)
        # = (96, 96, 50) + (0.5, -0.25, 1); rotation q_parent·q_child: heading 90 + 90 = 180.
        assert tuple(child.position.frame.origin) == pytest.approx((96.5, 95.75, 51.0), abs=1e-12)
        assert child.position.frame.get_heading() == pytest.approx(180.0, abs=1e-9)
        assert child.parent is parent
        assert parent.children.objects == [child]

    def test_the_child_takes_the_parents_cell_and_its_object_list(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        old_cell = child.cell
        assert child.set_parent(parent, -1, Frame(V(0.0, 0.5, 1.0)))
        # leave_world, then change_cell(parent->cell) (acclient.c:323016-323020).
        assert child.cell is parent.cell
        assert child.position.objcell_id == parent.position.objcell_id
        assert child in parent.cell.objects
        assert child not in old_cell.objects
        # recalc_cross_cells (323022) → calc_cross_cells shadows by the sorting sphere (acclient.c:322446):
        # r 0.9175 about (96, 96.5), so x 95.08-96.92 and y 95.58-97.42, the four cells around
        # (96, 96): (3, 3) 0x1C, (3, 4) 0x1D, (4, 3) 0x24, (4, 4) 0x25; none of its old ones.
        assert {shadow.cell.id for shadow in child.shadow_objects} == {
            0xA9B4001C,
            0xA9B4001D,
            0xA9B40024,
            0xA9B40025,
        }

    def test_refused_for_the_body_itself_and_for_a_part_it_does_not_have(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        # obj == this (acclient.c:316777); part_index == -1 || part_index < num_parts (316781).
        assert parent.add_child(parent, WHOLE_OBJECT, Frame()) is False
        assert child.set_parent(parent, 1, Frame()) is False  # the human has one part
        assert child.set_parent(None, 0, Frame()) is False
        assert child.parent is None
        assert parent.children is None

    def test_holding_ones_own_holder_is_an_error(self, world):
        # Retail refuses only obj == this (acclient.c:316777); a cycle would make
        # UpdateChildrenInternal and UpdateChild call each other until the stack overflows.
        grandparent = place(world, name="grandparent", origin=PARENT_AT)
        parent = place(world, name="parent", origin=(10.0, 10.0, 50.0))
        child = place(world, name="child", origin=(12.0, 10.0, 50.0))
        assert parent.set_parent(grandparent, WHOLE_OBJECT, Frame(V(0.0, 1.0, 0.0)))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 1.0, 0.0)))
        with pytest.raises(ValueError, match="'grandparent' cannot be held by 'child'"):
            grandparent.set_parent(child, WHOLE_OBJECT, Frame())
        assert grandparent.parent is None
        assert len(child.children or []) == 0
        # Two levels deep: the child is carried through its parent.
        assert tuple(child.position.frame.origin) == pytest.approx((96.0, 98.0, 50.0), abs=1e-12)

    def test_a_second_parent_takes_the_child_from_the_first(self, world):
        first = place(world, name="first", origin=PARENT_AT)
        second = place(world, name="second", origin=(100.0, 96.0, 50.0))
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(first, 0, Frame())
        assert child.set_parent(second, 0, Frame())
        # unset_parent before the new parent is taken (acclient.c:323015).
        assert len(first.children) == 0
        assert second.children.objects == [child]
        assert tuple(child.position.frame.origin) == pytest.approx((100.0, 96.0, 50.0), abs=1e-12)


class TestHeldLocations:
    """CPhysicsObj::set_parent @ 0x00515A90 (acclient.c:322951), add_child @ 0x0050F870 (316728),
    CSetup::GetHoldingLocation @ 0x005213F0 (336113)."""

    @staticmethod
    def _holder(world, **kwargs):
        body = place(world, name="holder", origin=PARENT_AT, **kwargs)
        body.part_array.setup.holding_locations = {1: LocationType(WHOLE_OBJECT, Frame(V(0.3, 0.0, 1.2)))}
        return body

    def test_the_location_gives_the_part_and_frame(self, world):
        holder = self._holder(world)
        child = place(world, name="sword", origin=(10.0, 10.0, 50.0))
        assert child.set_parent_at_location(holder, 1)
        # Frame::combine stores a float32 origin (ulp 7.6e-6 near 96 m).
        assert tuple(child.position.frame.origin) == pytest.approx((96.3, 96.0, 51.2), abs=2.0**-17)
        assert holder.children.location_ids == [1]
        assert holder.children.part_numbers == [WHOLE_OBJECT]

    def test_a_location_the_setup_lacks_is_refused(self, world):
        holder = self._holder(world)
        child = place(world, name="sword", origin=(10.0, 10.0, 50.0))
        assert child.set_parent_at_location(holder, 2) is False
        assert child.parent is None

    def test_a_hidden_parent_makes_the_child_nodraw_until_released(self, world):
        # BYTE1(parent state) & 0x40 is HIDDEN (0x4000); the child gets NODRAW (0x20)
        # (acclient.c:322986-322991), and unset_parent clears it again (320497-320502).
        holder = self._holder(world)
        holder.state |= PS.HIDDEN
        child = place(world, name="sword", origin=(10.0, 10.0, 50.0))
        assert child.set_parent_at_location(holder, 1)
        assert child.state & PS.NODRAW
        child.unset_parent()
        assert not child.state & PS.NODRAW


class TestCarried:
    """UpdateChildrenInternal @ 0x00513DA0 (acclient.c:321121) and UpdateChild @ 0x00512D50 (320038)."""

    def test_a_falling_parent_carries_its_child_and_the_child_never_steps(self, world):
        parent = place(world, name="parent", origin=(96.0, 96.0, 60.0))
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.5, 1.0)))
        physics = Physics(world)
        physics.add(parent)
        physics.add(child)
        parent_steps, child_steps = _steps(parent), _steps(child)
        for tick in range(1, 21):
            world.cur_time = tick * 0.05
            physics.use_time()
            # set_frame ends in UpdateChildrenInternal: the child is where the parent is, plus its offset.
            p = parent.position.frame.origin
            assert tuple(child.position.frame.origin) == pytest.approx((p.x, p.y + 0.5, p.z + 1.0), abs=1e-12)
        assert len(parent_steps) == 20
        assert parent.position.frame.origin.z < 60.0 - 4.0  # it fell about g/2 metres
        # update_object returns at once for a parented body (acclient.c:323099).
        assert child_steps == []

    def test_the_child_follows_its_parent_into_the_next_cell(self, world):
        # Cells are 24 m: x 95.9 is cell (3, 4) = 0x1D, x 96.23 is cell (4, 4) = 0x25 (1 + 8·cx + cy).
        parent = place(world, name="parent", origin=(95.9, 100.0, 50.0), state=PS(0))
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.0, 1.0)))
        assert child.position.objcell_id == 0xA9B4001D
        parent.set_velocity(V(10.0, 0.0, 0.0))
        world.cur_time = 1.0 / 30.0
        parent.update_object()
        assert parent.position.objcell_id == 0xA9B40025
        assert child.cell is parent.cell
        assert child.position.objcell_id == 0xA9B40025
        assert child in parent.cell.objects

    @pytest.mark.parametrize("held", [True, False])
    def test_other_bodies_pass_through_a_held_object(self, world, held):
        # CObjCell::find_obj_collisions skips shadows whose object has a parent (acclient.c:347159).
        parent = place(world, name="parent", origin=(96.0, 90.0, 50.0), state=PS(0))
        if held:
            child = place(world, name="child", origin=(10.0, 10.0, 50.0))
            assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 6.0, 0.0)))  # held at (96, 96, 50)
        else:
            place(world, name="child", origin=(96.0, 96.0, 50.0), state=PS(0))
        mover = place(world, name="mover", origin=(94.0, 96.0, 50.0), state=PS(0))
        mover.set_velocity(V(30.0, 0.0, 0.0))
        world.cur_time = 0.2
        mover.update_object()
        if held:
            # The whole float32 quantum's move: 94 + 30 · f32(0.2), to within the float32 rounding
            # of the sweep's steps along the 6-m path (a few ulps of 7.6e-6 at 100 m).
            assert mover.position.frame.origin.x == pytest.approx(94.0 + 30.0 * 0.20000000298023224, abs=1e-4)
        else:
            # The same body standing free blocks the mover short of it.
            assert mover.position.frame.origin.x < 96.0 - 0.9


class TestLettingGo:
    """unset_parent @ 0x00513470 (acclient.c:320479), unparent_children @ 0x005134E0 (320512),
    clear_transient_states @ 0x00511BF0 (319024)."""

    def test_a_released_child_restarts_its_clock_and_loses_its_transient_states(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0), on_ground=True)
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.5, 1.0)))
        child.transient_state |= TS.CONTACT | TS.ON_WALKABLE | TS.ACTIVE
        world.cur_time = 3.5
        child.unset_parent()
        assert child.parent is None
        assert len(parent.children) == 0
        # update_time = Timer::cur_time (320506), then clear_transient_states.
        assert child.update_time == 3.5
        assert not child.transient_state & (TS.CONTACT | TS.ON_WALKABLE | TS.ACTIVE)

    def test_a_released_child_runs_again_where_it_was_let_go(self, world):
        parent = place(world, name="parent", origin=PARENT_AT, state=PS(0))
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.5, 1.0)))
        world.cur_time = 1.0
        child.unset_parent()
        child.set_active(True)
        steps = _steps(child)
        world.cur_time = 1.0 + 1.0 / 30.0
        child.update_object()
        assert len(steps) == 1
        assert child.position.frame.origin.y == pytest.approx(96.5, abs=1e-12)

    def test_unparent_children_lets_every_child_go(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        children = [place(world, name=f"c{i}", origin=(10.0 + i, 10.0, 50.0)) for i in range(3)]
        for child in children:
            assert child.set_parent(parent, WHOLE_OBJECT, Frame())
        parent.unparent_children()
        assert len(parent.children) == 0
        assert all(child.parent is None for child in children)


class TestParts:
    """UpdateChild combines with ``parts[part_index]->pos.frame`` when the index is a part
    (acclient.c:320047-320050); parts sit at the body frame combined with their placement frame
    (CPartArray::UpdateParts, 326600)."""

    def test_a_child_on_part_1_rides_that_part(self, world):
        tree = build_box_tree(V(-0.5, -0.5, 0.0), V(0.5, 0.5, 1.0))
        setup = Setup(
            "cart",
            parts=[
                SetupPart(physics_bsp=tree, placement_frame=Frame(V(0.0, 0.0, 0.0))),
                SetupPart(physics_bsp=tree, placement_frame=Frame(V(2.0, 0.0, 0.0))),
            ],
        )
        parent = PhysicsObj(world, "cart", PartArray(setup))
        point = V(*PARENT_AT)
        assert parent.enter_world(Position(outdoor_cell_id(0xA9B4, point), Frame.from_heading(point, 90.0)))
        child = place(world, name="load", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, 1, Frame(V(0.0, 0.0, 1.0)))
        # Part 1 is at (96, 96, 50) + R(90°)·(2, 0, 0) = (96, 94, 50); the load 1 m above it.
        assert tuple(child.position.frame.origin) == pytest.approx((96.0, 94.0, 51.0), abs=1e-12)


class TestDeleteObject:
    """CObjectMaint::DeleteObject @ 0x00508460 (acclient.c:309917): exit_world, leave_world, out of
    the object table, then unset_parent and unparent_children."""

    def test_deleting_a_holder_lets_its_children_go(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.5, 1.0)))
        world.remove_object(parent)
        assert world.get_object(parent.id) is None
        assert child.parent is None
        assert len(parent.children) == 0

    def test_deleting_a_held_object_takes_it_off_its_parent(self, world):
        parent = place(world, name="parent", origin=PARENT_AT)
        child = place(world, name="child", origin=(10.0, 10.0, 50.0))
        assert child.set_parent(parent, WHOLE_OBJECT, Frame(V(0.0, 0.5, 1.0)))
        world.remove_object(child)
        assert len(parent.children) == 0
        assert child.cell is None
        assert child not in parent.cell.objects


class TestRandomHolding:
    """Random sequences of holding, letting go, deleting and moving keep retail's bookkeeping whole:
    a body is in its holder's CHILDLIST exactly when its ``parent`` is that holder, a held body
    shares its holder's cell and, when the holder is in the world, sits at its frame combined
    with its offset, every body with a cell is in that cell's object list once, and no coordinate
    is NaN. (Deleting a holder takes its children out of their cells before it lets them go,
    acclient.c:309925-309934, so they are left in none, and UpdateChild only runs for a holder
    with a cell, 323018; both as retail.)"""

    @pytest.mark.parametrize("seed", range(6))
    def test_the_bookkeeping_stays_whole(self, world, seed):
        import math
        import random

        rng = random.Random(seed)
        world.set_flat_ground(0xA9B4, 50.0)
        bodies = [
            place(world, name=f"b{i}", origin=(60.0 + 9.0 * i, 96.0, 50.0), on_ground=True, state=PS(0))
            for i in range(6)
        ]
        alive = list(bodies)
        world.cur_time = 0.0
        for _ in range(120):
            action = rng.choice(("hold", "hold", "release", "unparent", "move", "delete", "tick"))
            a, b = rng.choice(alive), rng.choice(alive)
            if action == "hold" and a is not b:
                try:
                    a.set_parent(b, WHOLE_OBJECT, Frame.from_heading(V(rng.uniform(-1, 1), 0.6, 1.0), 30.0))
                except ValueError as error:
                    assert "recurse forever" in str(error)
            elif action == "release":
                a.unset_parent()
            elif action == "unparent":
                a.unparent_children()
            elif action == "move" and a.parent is None and a.cell is not None:
                a.set_velocity(V(rng.uniform(-20, 20), rng.uniform(-20, 20), 0.0))
            elif action == "delete" and len(alive) > 2:
                world.remove_object(a)
                alive.remove(a)
            world.cur_time += 1.0 / 30.0
            for body in alive:
                body.update_object()
            for body in alive:
                origin = body.position.frame.origin
                assert not any(math.isnan(c) for c in origin)
                if body.parent is not None:
                    holder = body.parent
                    assert holder in alive
                    index = holder.children.find_child_index(body)
                    assert index is not None
                    assert body.cell is holder.cell
                    if holder.cell is None:
                        continue
                    expected = Frame()
                    expected.combine(holder.position.frame, holder.children.frames[index])
                    assert tuple(origin) == pytest.approx(tuple(expected.origin), abs=1e-9)
                if body.children is not None:
                    assert all(child.parent is body for child in body.children.objects)
                if body.cell is not None:
                    assert body.cell.objects.count(body) == 1
