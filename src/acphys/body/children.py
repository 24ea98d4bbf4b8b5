"""Parents and children: objects a body holds (a weapon in a hand, a shield, a torch).

A child has a ``parent`` and is carried, not simulated: ``update_object``
skips it, the sweep and other bodies ignore it, and every ``set_frame`` of
the parent puts each child at the parent's frame (or one of its parts')
combined with the child's own offset frame. The child shares the parent's
cell and follows it from cell to cell; its shadows are recomputed when it is
parented (``recalc_cross_cells``), not as the parent walks on, as in retail.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import PhysicsState, TransientState, member_namespace
from acphys.math.frame import Frame

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)

#: ``part_index`` 0xFFFFFFFF (-1): the child hangs off the parent's own frame, not a part's.
WHOLE_OBJECT = 0xFFFFFFFF


class ChildList:
    """Retail ``CHILDLIST``: the held objects, each with its offset frame, part and holding location."""

    def __init__(self) -> None:
        """Retail: CHILDLIST::CHILDLIST @ 0x0051B200 (acclient.c:329006)"""
        self.objects: list[PhysicsObj] = []
        self.frames: list[Frame] = []
        self.part_numbers: list[int] = []
        self.location_ids: list[int] = []

    def __len__(self) -> int:
        return len(self.objects)

    def add_child(self, obj: PhysicsObj, frame: Frame, part_no: int, location_id: int) -> None:
        """Append ``obj`` with a copy of ``frame``.

        Retail: CHILDLIST::add_child @ 0x0051B270 (acclient.c:329035)
        """
        self.objects.append(obj)
        self.frames.append(frame.copy())
        self.part_numbers.append(part_no)
        self.location_ids.append(location_id)

    def remove_child(self, obj: PhysicsObj) -> None:
        """Remove ``obj``, closing the gap.

        Retail drops the count by one and shifts the entries after ``obj`` down;
        an ``obj`` that is not in the list therefore drops the *last* entry
        (the search ends at the count, and nothing is shifted).

        Retail: CHILDLIST::remove_child @ 0x0051AF90 (acclient.c:328819)
        """
        if not self.objects:
            raise ValueError("CHILDLIST::remove_child on an empty list (retail's count would wrap)")
        index = next((i for i, child in enumerate(self.objects) if child is obj), len(self.objects) - 1)
        for entries in (self.objects, self.frames, self.part_numbers, self.location_ids):
            del entries[index]

    def find_child_index(self, child: PhysicsObj) -> int | None:
        """The index of ``child``, or None.

        Retail: CHILDLIST::FindChildIndex @ 0x0051B080 (acclient.c:328883)
        """
        return next((i for i, obj in enumerate(self.objects) if obj is child), None)


class Children:
    """Holding and being held (part of :class:`PhysicsObj`)."""

    def add_child(self, obj: PhysicsObj, part_index: int, frame: Frame) -> bool:
        """Hold ``obj`` at ``frame`` relative to part ``part_index`` (``WHOLE_OBJECT`` or -1: the body).

        Refused for the body itself and for a part the body does not have.
        The index is retail's unsigned int: -1 is ``WHOLE_OBJECT``.

        Retail: CPhysicsObj::add_child @ 0x0050F8F0 (acclient.c:316768)
        """
        if self.part_array is None:
            raise ValueError(f"{self.name!r} has no part array to hold {obj.name!r} by (retail would crash)")
        if obj is self:
            return False
        part_index &= 0xFFFFFFFF
        if part_index != WHOLE_OBJECT and part_index >= len(self.part_array.parts):
            return False
        if self.children is None:
            self.children = ChildList()
        self.children.add_child(obj, frame, part_index, 0)
        return True

    def add_child_at_location(self, obj: PhysicsObj, where: int) -> bool:
        """Hold ``obj`` at the setup's holding location ``where`` (its part and frame).

        Refused for the body itself, without a part array, or where the setup has no such location.

        Retail: CPhysicsObj::add_child @ 0x0050F870 (acclient.c:316728)
        """
        if obj is self or self.part_array is None:
            return False
        location = self.part_array.setup.holding_locations.get(where)
        if location is None:
            return False
        if self.children is None:
            self.children = ChildList()
        self.children.add_child(obj, location.frame, location.part_id, where)
        return True

    def set_parent(self, obj: PhysicsObj | None, part_index: int, frame: Frame) -> bool:
        """Become ``obj``'s child at ``frame`` on part ``part_index``.

        The body leaves any earlier parent and the world, takes the parent's cell, is put
        in place at once (``UpdateChild``) and shadows the cells it now overlaps.

        Retail: CPhysicsObj::set_parent @ 0x00515B50 (acclient.c:323002)
        """
        if obj is None:
            return False
        if obj is not self:
            self._refuse_cycle(obj)
        if not obj.add_child(self, part_index, frame):
            return False
        self._attach_to(obj)
        if obj.cell is not None:
            obj.update_child(self, part_index & 0xFFFFFFFF, frame)
            self.recalc_cross_cells()
        return True

    def set_parent_at_location(self, obj: PhysicsObj | None, where: int) -> bool:
        """Become ``obj``'s child at its setup's holding location ``where``.

        As :meth:`set_parent`; a parent that is ``HIDDEN`` also makes the child ``NODRAW``.

        Retail: CPhysicsObj::set_parent @ 0x00515A90 (acclient.c:322951)
        """
        if obj is None:
            return False
        if obj is not self:
            self._refuse_cycle(obj)
        if not obj.add_child_at_location(self, where):
            return False
        self._attach_to(obj)
        if obj.cell is not None and obj.children is not None:
            index = obj.children.find_child_index(self)
            if index is not None:
                obj.update_child(self, obj.children.part_numbers[index], obj.children.frames[index])
                self.recalc_cross_cells()
        if obj._state & PS.HIDDEN:
            self._state |= PS.NODRAW
        return True

    def _refuse_cycle(self, obj: PhysicsObj) -> None:
        """Raise when ``obj`` is this body or is held, at any depth, by it.

        Retail only refuses ``obj == this`` (acclient.c:316777): a longer cycle would make
        ``UpdateChildrenInternal`` recurse until the client's stack overflows.
        """
        holder: PhysicsObj | None = obj
        while holder is not None:
            if holder is self:
                raise ValueError(
                    f"{self.name!r} cannot be held by {obj.name!r}: {obj.name!r} is held by it "
                    "(retail would recurse forever)"
                )
            holder = holder.parent

    def _attach_to(self, obj: PhysicsObj) -> None:
        """What both ``set_parent`` overloads do once ``obj`` holds the body (acclient.c:322965-322970)."""
        self.unset_parent()
        self.leave_world()
        self.parent = obj
        if obj.cell is not None:
            self.change_cell(obj.cell)

    def unset_parent(self) -> None:
        """Stop being held: out of the parent's list (``NODRAW`` cleared under a ``HIDDEN``
        parent), the update clock restarted now, and the transient states cleared.

        Retail: CPhysicsObj::unset_parent @ 0x00513470 (acclient.c:320479)
        """
        parent = self.parent
        if parent is None:
            return
        if parent.children is not None:
            parent.children.remove_child(self)
        if parent._state & PS.HIDDEN:
            self._state &= ~PS.NODRAW
        self.parent = None
        self.update_time = self.world.cur_time
        self.clear_transient_states()

    def unparent_children(self) -> None:
        """Let go of every child, first to last, each as ``unset_parent`` does.

        Retail: CPhysicsObj::unparent_children @ 0x005134E0 (acclient.c:320512)
        """
        while self.children is not None and len(self.children):
            self.children.objects[0].unset_parent()

    def update_children_internal(self) -> None:
        """Put every child where it is held (bodies without a part array hold nothing).

        Retail: CPhysicsObj::UpdateChildrenInternal @ 0x00513DA0 (acclient.c:321121)
        """
        if self.part_array is None or self.children is None:
            return
        children = self.children
        index = 0
        while index < len(children):
            self.update_child(children.objects[index], children.part_numbers[index], children.frames[index])
            index += 1

    def update_child(self, child: PhysicsObj, part_index: int, child_frame: Frame) -> None:
        """Set ``child``'s frame to part ``part_index``'s frame (the body's own for an index past
        the parts, such as ``WHOLE_OBJECT``) combined with ``child_frame``, then run the child's
        particles and scripts.

        Retail: CPhysicsObj::UpdateChild @ 0x00512D50 (acclient.c:320038)
        """
        parts = self.part_array.parts
        base = parts[part_index].pos.frame if part_index < len(parts) else self.position.frame
        new_frame = Frame()
        new_frame.combine(base, child_frame)
        child.set_frame(new_frame)
        if child.particle_manager is not None:
            child.particle_manager.update_particles()
        if child.script_manager is not None:
            child.script_manager.update_scripts()

    def recalc_cross_cells(self) -> None:
        """Recompute the shadows of the body and, recursively, of its children.

        A body in no cell has none to recompute (retail's examination objects, a UI
        preview, shadow their particles instead; not ported).

        Retail: CPhysicsObj::recalc_cross_cells @ 0x00515A30 (acclient.c:322917)
        """
        if self.part_array is None or not self.position.objcell_id:
            return
        self.calc_cross_cells()
        if self.children is not None:
            for child in list(self.children.objects):
                child.recalc_cross_cells()

    def clear_transient_states(self) -> None:
        """Off the ground (telling the movement manager when it was on walkable ground), with no
        contact, water, sliding, stationary, active or ethereal-check state.

        Retail: CPhysicsObj::clear_transient_states @ 0x00511BF0 (acclient.c:319024)
        """
        self._transient_state &= ~TS.CONTACT
        self.calc_acceleration()
        was_on_walkable = bool(self._transient_state & TS.ON_WALKABLE)
        self._transient_state &= ~(TS.ON_WALKABLE | TS.WATER_CONTACT)
        if was_on_walkable and self.movement_manager is not None:
            self.movement_manager.leave_ground()
        self.calc_acceleration()
        self._transient_state &= ~(
            TS.SLIDING
            | TS.STATIONARY_FALL
            | TS.STATIONARY_STOP
            | TS.STATIONARY_STUCK
            | TS.ACTIVE
            | TS.CHECK_ETHEREAL
        )
