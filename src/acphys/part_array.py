"""``CPartArray``: the body's setup, animation sequence and motion-table manager, as the tick sees them."""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import TransitionState, member_namespace
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.animation import AnimFrame
from acphys.motion.movement import MovementError, MovementParameters, MovementStruct, MovementType
from acphys.motion.sequence import Sequence
from acphys.motion.table_manager import MotionTableManager
from acphys.physics_part import PhysicsPart
from acphys.precision import f32, pack3, unpack3
from acphys.setup import Setup

ME = member_namespace(MovementError)
MT = member_namespace(MovementType)

if TYPE_CHECKING:
    from acphys.geometry.sphere import SphereTransition
    from acphys.motion.motion_table import MotionTable
    from acphys.physics_obj import PhysicsObj
    from acphys.world.obj_cell import CellArray, ObjCell


#: The placement ``CPartArray::CreateSetup`` asks for (``SetPlacementFrame(0x65)``, acclient.c:326973).
DEFAULT_PLACEMENT_ID = 0x65


def combine_scaled(dst: Frame, f1: Frame, f2: Frame, scale: float) -> None:
    """``dst = f1 ∘ f2`` with ``f2``'s offset scaled by ``scale`` (a part placed on its body).

    The scaled offset stays in registers; the origin sums run x, z, y then ``f1``'s origin, and
    the quaternion keeps this overload's order of operands (acclient.c:326581-326597). ``dst``
    must not be ``f1`` or ``f2``.

    Retail: Frame::combine @ 0x00518FD0 (acclient.c:326562)
    """
    m = f1.m
    o = f2.origin
    sx, sy, sz = o.x * scale, o.y * scale, o.z * scale
    fo = f1.origin
    dst.origin.x, dst.origin.y, dst.origin.z = unpack3(
        pack3(
            sx * m[0] + sz * m[6] + sy * m[3] + fo.x,
            sx * m[1] + sz * m[7] + sy * m[4] + fo.y,
            sx * m[2] + sz * m[8] + sy * m[5] + fo.z,
        )
    )
    w1, x1, y1, z1 = f1.qw, f1.qx, f1.qy, f1.qz
    w2, x2, y2, z2 = f2.qw, f2.qx, f2.qy, f2.qz
    dst.set_rotate(
        w2 * w1 - x2 * x1 - y2 * y1 - z2 * z1,
        x2 * w1 + w2 * x1 + z2 * y1 - y2 * z1,
        w1 * y2 - x1 * z2 + x2 * z1 + w2 * y1,
        w1 * z2 + x1 * y2 - x2 * y1 + w2 * z1,
    )


class PartArray:
    """Retail ``CPartArray`` (acclient.h:30762): owns the setup, the sequence and the motion tables.

    ``scale`` is the part array's (uniform) scale, kept equal to the body's
    ``m_scale`` by ``CPhysicsObj::SetScaleStatic``; it is a float32 (retail's is a
    ``Vector3`` of floats). ``parts`` holds one part per
    ``setup.parts`` entry (``InitParts``, acclient.c:325273), or the one part of a setup without
    that list. A many-part array starts in its default placement: ``CPartArray::CreateSetup``
    (acclient.c:326946) calls ``SetPlacementFrame(0x65)``, which hands the sequence the setup's
    per-part placement frames (acphys setups carry only that one placement, see
    :class:`~acphys.setup.SetupPart`).
    """

    __slots__ = ("motion_table_manager", "owner", "parts", "scale", "sequence", "setup")

    def __init__(self, setup: Setup, owner: PhysicsObj | None = None) -> None:
        self.setup = setup
        self.owner = owner
        self.scale = 1.0
        self.sequence = Sequence()
        self.sequence.set_object(owner)
        if setup.parts is None:
            self.parts: list[PhysicsPart] = [PhysicsPart(setup)]
        else:
            self.parts = [PhysicsPart(setup, part) for part in setup.parts]
            placement = AnimFrame([part.placement_frame.copy() for part in setup.parts])
            self.sequence.set_placement_frame(placement, DEFAULT_PLACEMENT_ID)
        self.motion_table_manager: MotionTableManager | None = None

    def set_owner(self, owner: PhysicsObj) -> None:
        """Attach the array to its body: the sequence's hooks and the manager's completions go there."""
        self.owner = owner
        self.sequence.set_object(owner)
        if self.motion_table_manager is not None:
            self.motion_table_manager.physics_obj = owner

    def set_motion_table(self, table: MotionTable | None) -> None:
        """Give the body a motion table (or take it away), with a fresh manager.

        acphys passes the table itself where retail passes its DAT id; the
        cached-id shortcut becomes "same table object".

        Retail: CPartArray::SetMotionTableID @ 0x005186E0 (acclient.c:325981)
        """
        manager = self.motion_table_manager
        if manager is not None and manager.table is table:
            return
        self.motion_table_manager = None if table is None else MotionTableManager(table, self.owner)

    # -- the tick --------------------------------------------------------------------------

    def update(self, quantum: float, offset_frame: Frame) -> None:
        """Advance the sequence, writing root motion into ``offset_frame``.

        ``quantum`` is a ``float`` parameter: the sequence plays the float32 quantum.

        Retail: CPartArray::Update @ 0x00517DB0 (acclient.c:325139)
        """
        self.sequence.update(f32(quantum), offset_frame)

    def handle_movement(self) -> None:
        """Tick the motion-table manager, if there is one.

        Retail: CPartArray::HandleMovement @ 0x00517D60 (acclient.c:325105)
        """
        if self.motion_table_manager is not None:
            self.motion_table_manager.use_time()

    def has_anims(self) -> bool:
        """Retail: CPartArray::HasAnims @ 0x00517D40 (acclient.c:325089)"""
        return self.sequence.has_anims()

    # -- motion-table requests -------------------------------------------------------------

    def _perform(self, ms: MovementStruct) -> int:
        if self.motion_table_manager is None:
            return ME.NO_ANIMATION_TABLE
        return self.motion_table_manager.perform_movement(ms, self.sequence)

    def do_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Play ``motion`` through the motion table (error 7 without one).

        Retail: CPartArray::DoInterpretedMotion @ 0x00518750 (acclient.c:326017)
        """
        return self._perform(MovementStruct(MT.INTERPRETED_COMMAND, motion, params=params))

    def stop_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPartArray::StopInterpretedMotion @ 0x005187F0 (acclient.c:326053)"""
        return self._perform(MovementStruct(MT.STOP_INTERPRETED_COMMAND, motion, params=params))

    def stop_completely_internal(self) -> int:
        """Retail: CPartArray::StopCompletelyInternal @ 0x00518890 (acclient.c:326089)"""
        return self._perform(MovementStruct(MT.STOP_COMPLETELY))

    def animation_done(self, success: bool) -> None:
        """Retail: CPartArray::AnimationDone @ 0x00517D30 (acclient.c:325079)"""
        if self.motion_table_manager is not None:
            self.motion_table_manager.animation_done(success)

    def check_for_completed_motions(self) -> None:
        """Retail: CPartArray::CheckForCompletedMotions @ 0x00517D50 (acclient.c:325095)"""
        if self.motion_table_manager is not None:
            self.motion_table_manager.check_for_completed_motions()

    def initialize_motion_tables(self) -> None:
        """Put the sequence into the table's default state.

        Retail: CPartArray::InitializeMotionTables @ 0x00517D10 (acclient.c:325067)
        """
        if self.motion_table_manager is not None:
            self.motion_table_manager.initialize_state(self.sequence)

    def handle_enter_world(self) -> None:
        """Drop link animations (``CPhysicsObj::RemoveLinkAnimations`` lands here).

        Retail: CPartArray::HandleEnterWorld @ 0x00517D70 (acclient.c:325115)
        """
        if self.motion_table_manager is not None:
            self.motion_table_manager.handle_enter_world(self.sequence)

    def handle_exit_world(self) -> None:
        """Force every pending motion to complete, unsuccessfully.

        Retail: CPartArray::HandleExitWorld @ 0x00517D90 (acclient.c:325127)
        """
        if self.motion_table_manager is not None:
            self.motion_table_manager.handle_exit_world()

    # -- setup data, scaled ---------------------------------------------------------------

    def get_num_sphere(self) -> int:
        """Retail: CPartArray::GetNumSphere @ 0x00518060 (acclient.c:325357)"""
        return len(self.setup.spheres)

    def get_sphere(self) -> list[Sphere]:
        """Retail: CPartArray::GetSphere @ 0x00518070 (acclient.c:325363)"""
        return self.setup.spheres

    def get_num_cylsphere(self) -> int:
        """Retail: CPartArray::GetNumCylsphere @ 0x00518080 (acclient.c:325369)"""
        return len(self.setup.cylspheres)

    def get_cylsphere(self) -> list[CylSphere]:
        """Retail: CPartArray::GetCylsphere @ 0x00518090 (acclient.c:325375)"""
        return self.setup.cylspheres

    def allows_free_heading(self) -> bool:
        """Retail: CPartArray::AllowsFreeHeading @ 0x005180C0 (acclient.c:325393)"""
        return self.setup.allow_free_heading

    def get_sorting_sphere(self) -> Sphere:
        """Retail: CPartArray::GetSortingSphere @ 0x00518B00 (acclient.c:326267)"""
        return self.setup.sorting_sphere

    def get_height(self) -> float:
        """Retail: CPartArray::GetHeight @ 0x005180B0 (acclient.c:325387)"""
        return self.setup.height * self.scale

    def get_radius(self) -> float:
        """Retail: CPartArray::GetRadius @ 0x005180A0 (acclient.c:325381)"""
        return self.setup.radius * self.scale

    def get_step_up_height(self) -> float:
        """Retail: CPartArray::GetStepUpHeight @ 0x005180D0 (acclient.c:325399)"""
        return self.setup.step_up_height * self.scale

    def get_step_down_height(self) -> float:
        """Retail: CPartArray::GetStepDownHeight @ 0x005180F0 (acclient.c:325413)"""
        return self.setup.step_down_height * self.scale

    # -- the parts ------------------------------------------------------------------------

    def set_scale_internal(self, new_scale: float) -> None:
        """Take ``new_scale``; every part's ``gfxobj_scale`` becomes it times the part's
        ``default_scale`` per axis, or ``new_scale`` itself for a setup without part descriptions
        (retail: no ``default_scale`` array).

        Retail: CPartArray::SetScaleInternal @ 0x00518A00 (acclient.c:326181)
        """
        new_scale = self.scale = f32(new_scale)
        if self.setup.parts is None:
            for part in self.parts:
                part.gfxobj_scale = Vector3(new_scale, new_scale, new_scale)
        else:
            for part, desc in zip(self.parts, self.setup.parts, strict=True):
                default = desc.default_scale
                part.gfxobj_scale = Vector3(
                    default.x * new_scale, default.y * new_scale, default.z * new_scale
                )
        self._shadows_moved()

    def set_cell_id(self, cell_id: int) -> None:
        """Retail: CPartArray::SetCellID @ 0x00517DD0 (acclient.c:325145)"""
        for part in self.parts:
            part.pos.objcell_id = cell_id
        self._shadows_moved()

    def set_frame(self, frame: Frame) -> None:
        """Place the parts at the body's ``frame`` (lights are not ported).

        Retail: CPartArray::SetFrame @ 0x00519310 (acclient.c:326765)
        """
        self.update_parts(frame)
        self._shadows_moved()

    def _shadows_moved(self) -> None:
        """Not retail: the body's place, cell or scale changed, so crowded cells file its shadows
        again (``CellMembership.shadows_moved``). Every such change of a body reaches its part
        array, which is why the call is made here."""
        if self.owner is not None:
            self.owner.shadows_moved()

    def update_parts(self, frame: Frame) -> None:
        """Each part's frame is ``frame`` combined with its frame in the current animation frame
        (or placement frame), whose offset is scaled by ``scale`` (:func:`combine_scaled`);
        only as many parts as both have.

        With neither (a setup without part descriptions brings no placement frame) the single
        part sits at the setup origin, so its frame is ``frame`` itself.

        Retail: CPartArray::UpdateParts @ 0x005190F0 (acclient.c:326600)
        """
        anim_frame = self.sequence.get_curr_animframe()
        if anim_frame is None:
            for part in self.parts:
                part.pos.frame.assign(frame)
            return
        scale = self.scale
        for part, part_frame in zip(self.parts, anim_frame.frames, strict=False):
            combine_scaled(part.pos.frame, frame, part_frame, scale)

    def find_obj_collisions(self, transition: SphereTransition) -> TransitionState:
        """Each part in turn (``PhysicsPart.find_obj_collisions``) until one answers other than OK;
        that answer, else OK.

        Retail: CPartArray::FindObjCollisions @ 0x00518180 (acclient.c:325463)
        """
        for part in self.parts:
            result = part.find_obj_collisions(transition)
            if result != TransitionState.OK:
                return result
        return TransitionState.OK

    def calc_cross_cells_static(self, cell: ObjCell, cell_array: CellArray) -> None:
        """Add the cells the parts' bounding boxes reach from ``cell`` (its parts overload of
        ``find_transit_cells``).

        Retail: CPartArray::calc_cross_cells_static @ 0x00518160 (acclient.c:325457)
        """
        cell.find_transit_cells_for_parts(self.parts, cell_array)
