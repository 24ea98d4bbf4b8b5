"""Float32 at rest in the managers: representative retail ``float`` stores, worked by hand.

Each expected value follows the cited decompiled lines: a ``float`` field, local, spill or parameter is
narrowed (``f32``) where retail stores it, everything between two stores is double. The inputs are
chosen so that the float32 result differs from an all-double one (asserted alongside), so each test pins
the store it names. The last tests check that the managers' ``float`` fields hold float32 values after
real use, and that global detection reports in the retail ``LongNIHash`` order.

Decompiled: cpmanager/CInterpolationManager.c, CStickyManager.c, CConstraintManager.c;
cphysobj/CTargetting.c, CDetectionCylsphere.c, CParticleManager.c, CParticleEmitter.c,
CParticleEmitterInfo.c; canim/CPhysicsScriptTable.c.
"""

from __future__ import annotations

import math

import pytest

from acphys.managers.detection import DetectionInfo, DetectionManager, DetectionType
from acphys.managers.interpolation import InterpolationManager
from acphys.managers.particles import (
    EmitterType,
    Particle,
    ParticleEmitterInfo,
    ParticlePart,
    ParticleType,
    register_emitter_info,
    unregister_emitter_info,
)
from acphys.managers.scripts import PhysicsScriptTableData, ScriptAndModData
from acphys.managers.sticky import STICKY_RADIUS
from acphys.managers.target import TargetInfo, TargetManager, TargetStatus
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32, is_f32
from acphys.world.world import World
from support import LANDBLOCK, place

DT = 1.0 / 30.0
GROUND = 50.0
EMITTER_INFO = 0x32000F32


@pytest.fixture(autouse=True)
def _ground(world: World) -> None:
    world.set_flat_ground(LANDBLOCK, GROUND)


def _grounded(world: World, x: float = 40.0, y: float = 100.0, name: str = "body") -> PhysicsObj:
    return place(world, name=name, on_ground=True, origin=(x, y, GROUND))


def _there(body: PhysicsObj, dx: float, dy: float = 0.0) -> Position:
    """The body's position moved by (dx, dy), stored float32 as a Vector3 is."""
    here = body.position.frame.origin
    point = Vector3(here.x + dx, here.y + dy, here.z)
    return Position(outdoor_cell_id(LANDBLOCK, point), Frame(point))


class TestInterpolation:
    def test_the_glide_step_is_cut_with_float_locals(self, world: World) -> None:
        body = _grounded(world)
        target = _there(body, 3.3)
        body.interpolate_to(target, False)
        offset = Frame()
        body.position_manager.adjust_offset(offset, DT)
        # The adjustment is (dx, 0, 0) with dx = f32(43.3) - 40 (exact); my_max_speed = f32(4 * 2),
        # progress_madea = f32(my_max_speed * quantum), adjustment_distance = f32(|dx|) and the scale
        # _rhs = f32(progress_madea / adjustment_distance) are float stores, Vector3::operator*= stores
        # the product (acclient.c:389237, 389255-389263).
        dx = f32(43.3) - 40.0
        step = f32(8.0 * DT)
        expected = f32(dx * f32(step / dx))
        assert offset.origin.x == expected
        assert expected != dx * (8.0 * DT / dx)
        assert offset.origin.y == 0.0

    def test_progress_quantum_is_a_float_sum(self, world: World) -> None:
        body = _grounded(world)
        body.interpolate_to(_there(body, 3.0), False)
        manager = body.position_manager.interpolation_manager
        for _ in range(3):
            body.position_manager.adjust_offset(Frame(), DT)
        # progress_quantum = quantum + progress_quantum, a float field (acclient.c:389242).
        assert manager.frame_counter == 3
        assert manager.progress_quantum == f32(DT + f32(DT + f32(DT + 0.0)))
        assert manager.progress_quantum != DT + DT + DT

    def test_the_next_node_distance_is_a_float_field(self, world: World) -> None:
        body = _grounded(world)
        manager = InterpolationManager(body)
        manager.interpolate_to(_there(body, 3.0), False)
        manager.interpolate_to(_there(body, 3.0, 1.0), False)
        manager.node_completed(True)
        # NodeCompleted: original_distance = Position::distance to the next node (acclient.c:388917):
        # sqrt(3² + 1²) narrowed.
        assert manager.original_distance == f32(math.sqrt(10.0)) != math.sqrt(10.0)


class TestSticky:
    def test_within_reach_the_step_is_the_float_gap(self, world: World) -> None:
        pet = _grounded(world, name="pet")
        pet.get_minterp()
        far = 0x7FFF0000
        pet.make_position_manager().stick_to(far, 0.17, 0.0)
        reported = _there(pet, 1.31)
        pet.handle_update_target(TargetInfo(far, TargetStatus.OK, reported))
        offset = Frame()
        pet.position_manager.adjust_offset(offset, DT)
        sticky = pet.position_manager.sticky_manager
        # target_radius is a float parameter and field (acclient.c:388681); GetRadius is passed as a float
        # (388558); mag = cylinder_distance_no_z - 0.30000001 is a float local (388559); |mag| is within
        # the 20 m/s step, so the step is mag along the local x (388583-388592).
        assert sticky.target_radius == f32(0.17) != 0.17
        d = f32(41.31) - 40.0
        gap = (d - (f32(pet.get_radius()) + f32(0.17))) - STICKY_RADIUS
        mag = f32(gap)
        assert offset.origin.x == mag != gap
        assert offset.origin.y == 0.0


class TestConstraint:
    def test_the_leash_fields_and_the_scale_are_floats(self, world: World) -> None:
        body = _grounded(world)
        body.constrain_to(_there(body, 19.0), 10.0, 19.9)
        constraint = body.position_manager.constraint_manager
        # ConstrainTo: the float parameters and the distance are stored in float fields (389524-389526).
        assert constraint.constraint_distance_max == f32(19.9) != 19.9
        assert constraint.constraint_pos_offset == 19.0
        offset = Frame()
        offset.origin.set(Vector3(1.0, 0.0, 0.0))
        body.position_manager.adjust_offset(offset, DT)
        # _rhs = (max - total) / (max - start) is a float argument (389493-389495); the total then adds
        # the scaled length, stored in the float field (389506).
        scale = f32((f32(19.9) - 19.0) / (f32(19.9) - 10.0))
        assert offset.origin.x == scale
        assert scale != f32((19.9 - 19.0) / (19.9 - 10.0))
        assert constraint.constraint_pos_offset == f32(scale + 19.0)


class TestTarget:
    def test_the_interpolated_position_spills_only_its_z_term(self, world: World) -> None:
        target = place(world, name="target", spheres=False, origin=(14.7, 96.0, 58.2))
        target.cached_velocity = Vector3(3.7, 0.0, 3.4)
        p = TargetManager(target).get_interpolated_position(1.69)
        # quantum is a float local; quantum * v.x and * v.y stay in registers, quantum * v.z is stored
        # in a Vector3 before the sums are stored into the origin (acclient.c:328147-328154).
        q = f32(1.69)
        vx, vz, ox, oz = f32(3.7), f32(3.4), f32(14.7), f32(58.2)
        assert p.frame.origin.x == f32(q * vx + ox) != f32(f32(q * vx) + ox)
        assert p.frame.origin.z == f32(f32(q * vz) + oz) != f32(q * vz + oz)

    def test_the_radius_is_a_float_parameter(self, world: World) -> None:
        tracker = _grounded(world, name="tracker")
        target = _grounded(world, 45.0, name="target")
        tracker.set_target(0, target.id, 0.7, 0.5)
        # SetTarget and AddVoyeur take the radius as a float (acclient.c:328617, 328377); the report
        # carries the voyeur's radius back (328091-328123).
        assert tracker.target_manager.target_info.radius == f32(0.7) != 0.7
        voyeur = next(iter(target.target_manager.voyeur_table))
        assert voyeur.radius == f32(0.7)


class TestParticles:
    def _particle(self, particle_type: ParticleType, t: float, **vectors: Vector3) -> tuple[Particle, float]:
        particle = Particle()
        particle.birthtime = 5.0
        particle.lifespan = 10.0
        for name, value in vectors.items():
            setattr(particle, name, value)
        return particle, 5.0 + t

    def test_local_velocity_adds_the_unspilled_x_base(self) -> None:
        particle, now = self._particle(
            ParticleType.LOCAL_VELOCITY, 0.34, offset=Vector3(0.49, 0.0, 0.0), a=Vector3(2.1, 0.0, 0.0)
        )
        parent = Frame(Vector3(10.9, 0.0, 0.0))
        part = ParticlePart()
        particle.update(ParticleType.LOCAL_VELOCITY, False, part, parent, now)
        # Case 2: x = f32((parent.x + offset.x) + f32(t·a.x)), the base in registers
        # (acclient.c:330422-330429).
        t = now - 5.0
        px, ox, ax = f32(10.9), f32(0.49), f32(2.1)
        assert part.frame.origin.x == f32((px + ox) + f32(t * ax))
        assert part.frame.origin.x != f32(f32(px + ox) + f32(t * ax))
        assert part.frame.origin.x != f32(px + ox + t * ax)

    def test_parabolic_spills_a_float32_copy_of_the_lifetime(self) -> None:
        particle, now = self._particle(
            ParticleType.PARABOLIC_LVGA,
            0.72,
            offset=Vector3(0.0, 0.25, 0.0),
            a=Vector3(0.0, 0.5, 0.0),
            b=Vector3(0.0, -8.3, 0.0),
        )
        parent = Frame(Vector3(0.0, 3.5, 0.0))
        part = ParticlePart()
        particle.update(ParticleType.PARABOLIC_LVGA, False, part, parent, now)
        # Case 3, y: v24 = f32(b.y·0.5), v27 = f32(v24·t), v29 = f32(t), v31 = f32(v27·v29),
        # v36 = f32(offset.y + parent.y), result.y = f32(t·a.y), w.y = f32(v36 + result.y),
        # y = f32(w.y + v31) (acclient.c:330435-330465).
        t = now - 5.0
        by = f32(-8.3)
        half_bt2 = f32(f32(f32(by * 0.5) * t) * f32(t))
        expected = f32(f32(f32(0.25 + 3.5) + f32(t * 0.5)) + half_bt2)
        assert part.frame.origin.y == expected
        assert expected != f32(f32(f32(0.25 + 3.5) + f32(t * 0.5)) + f32(f32(by * 0.5) * t * t))

    def test_scale_and_translucency_are_float_stores(self) -> None:
        particle, now = self._particle(ParticleType.STILL, 0.1)
        particle.start_scale, particle.final_scale = f32(0.3), f32(1.7)
        particle.start_trans, particle.final_trans = f32(0.1), f32(0.9)
        part = ParticlePart()
        particle.update(ParticleType.STILL, False, part, Frame(), now)
        # fraction = lifetime / lifespan (double); the scale vector and the translucency are float
        # stores (acclient.c:330538-330549).
        fraction = (now - 5.0) / 10.0
        scale = f32((f32(1.7) - f32(0.3)) * fraction + f32(0.3))
        assert part.gfxobj_scale.exactly_equals(Vector3(scale, scale, scale))
        assert part.translucency == f32((f32(0.9) - f32(0.1)) * fraction + f32(0.1))

    def test_the_random_magnitude_is_a_float_spill(self) -> None:
        info = ParticleEmitterInfo(a=Vector3(0.14, 0.0, 0.0), min_a=1.29, max_a=2.2)

        class Dice:
            def uniform(self, lower: float, upper: float) -> float:
                return lower + (upper - lower) * 0.84

        # a_mag = (max_a - min_a) · roll + min_a is a float spill (acclient.c:324608).
        mag = f32((f32(2.2) - f32(1.29)) * 0.84 + f32(1.29))
        a = info.get_random_a(Dice())  # type: ignore[arg-type]
        assert a.x == f32(f32(0.14) * mag)
        assert a.x != f32(f32(0.14) * ((f32(2.2) - f32(1.29)) * 0.84 + f32(1.29)))

    def test_the_sorting_radius_is_a_float_local(self) -> None:
        info = ParticleEmitterInfo(max_a=1.3, lifespan=0.7)
        # velocity_radius = max_a · lifespan is a float local (acclient.c:324489).
        assert info.sorting_sphere_radius == f32(f32(1.3) * 0.7) != f32(1.3) * 0.7


class TestScripts:
    def test_the_intensity_is_compared_as_a_float(self) -> None:
        data = PhysicsScriptTableData([ScriptAndModData(0.7, 0x33000001), ScriptAndModData(1.0, 0x33000002)])
        # GetScript(float mod): mod > (double)entry.mod (acclient.c:336564) with both float32 0.7: equal, so
        # the first variant plays (in doubles 0.7 > f32(0.7) would skip it).
        assert data.script_array[0].mod == f32(0.7)
        assert data.get_script(0.7) == 0x33000001


GLOBAL = 0


@pytest.fixture
def lookout(world: World) -> tuple[PhysicsObj, DetectionManager]:
    watcher = place(world, name="watcher", spheres=False, origin=(96.0, 96.0, GROUND), on_ground=True)
    watcher.detection_manager = DetectionManager(watcher)
    watcher.detection_manager.create_detection_cylsphere(GLOBAL, 10.0, 0)
    return watcher, watcher.detection_manager


def _check_at(manager: DetectionManager, t: float) -> None:
    manager.physobj.world.physics_time = t
    manager.check_detection()


class TestGlobalDetectionOrder:
    # Arrival order, and the bucket (id ^ id >> 16) % 32 of LongNIHash::add (acclient.c:327173): 0x50001 is
    # bucket 4 (0x50001 % 32 would be 1), 33 and 1 bucket 1, 3 bucket 3, 2 and 34 bucket 2.
    ARRIVALS = (0x50001, 33, 3, 1, 2, 34)
    # The 1-Hz pass walks the 32 buckets in order, each chain from its head, and add puts each new entry
    # at the head (acclient.c:327182-327183, 327054-327071, 327406-327423): newest first in a bucket.
    REPORTED = (1, 33, 34, 2, 3, 0x50001)

    def test_entered_reports_come_in_bucket_order(self, lookout: tuple[PhysicsObj, DetectionManager]) -> None:
        watcher, manager = lookout
        _check_at(manager, 1.0)  # makes the 32-bucket table (InitializeGlobalDetection, acclient.c:327214)
        for object_id in self.ARRIVALS:
            watcher.receive_detection_update(DetectionInfo(object_id, DetectionType.ENTERED))
        _check_at(manager, 2.0)
        assert [object_id for _, _, object_id, _ in manager.reports] == list(self.REPORTED)
        assert list(self.ARRIVALS) != list(self.REPORTED)

    def test_left_reports_come_in_bucket_order_and_are_dropped_on_the_way(
        self, lookout: tuple[PhysicsObj, DetectionManager]
    ) -> None:
        watcher, manager = lookout
        _check_at(manager, 1.0)
        for object_id in self.ARRIVALS:
            watcher.receive_detection_update(DetectionInfo(object_id, DetectionType.ENTERED))
        _check_at(manager, 2.0)
        for object_id in reversed(self.ARRIVALS):
            watcher.receive_detection_update(DetectionInfo(object_id, DetectionType.LEFT))
        _check_at(manager, 3.0)
        # ReportGlobalDetection steps the iterator before it removes a Left entry (acclient.c:327423,
        # 327443): every Left is reported, in the table's order, and the table ends empty.
        lefts = [(object_id, status) for _, _, object_id, status in manager.reports[len(self.ARRIVALS) :]]
        assert lefts == [(object_id, DetectionType.LEFT) for object_id in self.REPORTED]
        assert len(manager.detection_objects) == 0


class TestStoredFieldsAreFloat32:
    def test_after_real_use(self, world: World) -> None:
        pet = _grounded(world, name="pet")
        pet.get_minterp()
        owner = _grounded(world, 45.3, name="owner")
        remote = _grounded(world, 60.0, 90.0, name="remote")
        remote.interpolate_to(_there(remote, 3.3, 0.7), False)
        remote.constrain_to(_there(remote, 1.1), 2.3, 7.7)
        pet.stick_to_object(owner.id)
        pet.set_target_quantum(0.37)
        world.player = pet  # the viewer the particle object measures its CYpt from
        register_emitter_info(
            EMITTER_INFO,
            ParticleEmitterInfo(
                emitter_type=EmitterType.BIRTHRATE_PER_SEC,
                particle_type=ParticleType.PARABOLIC_LVGAGR,
                hw_gfxobj_id=0x01000001,
                birthrate=0.1,
                max_particles=3,
                initial_particles=1,
                lifespan=1.3,
                lifespan_rand=0.3,
                offset_dir=Vector3(0.0, 0.0, 1.0),
                min_offset=0.1,
                max_offset=0.7,
                a=Vector3(0.3, 1.1, 0.7),
                min_a=0.7,
                max_a=1.3,
                b=Vector3(0.0, 0.0, -9.8),
                c=Vector3(0.0, 0.0, 1.3),
                start_scale=0.3,
                final_scale=1.7,
                scale_rand=0.1,
                start_trans=0.1,
                final_trans=0.9,
                trans_rand=0.05,
            ),
        )
        try:
            emitter_id = owner.create_particle_emitter(EMITTER_INFO, -1, Frame(Vector3(0.1, 0.2, 1.3)), 0)
            assert emitter_id
            for step in range(1, 16):
                world.cur_time = step * DT
                for body in (pet, owner, remote):
                    body.update_object()
            emitter = owner.particle_manager.get_emitter(emitter_id)
            assert emitter is not None and emitter.num_particles > 0
            values: dict[str, float] = {}
            interp = remote.position_manager.interpolation_manager
            values["original_distance"] = interp.original_distance
            values["progress_quantum"] = interp.progress_quantum
            constraint = remote.position_manager.constraint_manager
            values["constraint_pos_offset"] = constraint.constraint_pos_offset
            values["constraint_distance_start"] = constraint.constraint_distance_start
            values["constraint_distance_max"] = constraint.constraint_distance_max
            values["target_radius"] = pet.position_manager.sticky_manager.target_radius
            values["target_info.radius"] = pet.target_manager.target_info.radius
            voyeur = next(iter(owner.target_manager.voyeur_table))
            values["voyeur.radius"] = voyeur.radius
            values["voyeur.quantum"] = voyeur.quantum  # a double field, narrowed by add_voyeur's float
            values["degrade_distance"] = emitter.degrade_distance
            values["viewer_distance"] = emitter.viewer_distance()
            info = emitter.info
            for name in (
                "min_offset",
                "max_offset",
                "min_a",
                "max_a",
                "scale_rand",
                "start_scale",
                "final_scale",
                "trans_rand",
                "start_trans",
                "final_trans",
                "sorting_sphere_radius",
            ):
                values[f"info.{name}"] = getattr(info, name)
            for index, part in emitter.live_particles():
                particle = emitter.particles[index]
                for name in ("start_scale", "final_scale", "start_trans", "final_trans"):
                    values[f"particle{index}.{name}"] = getattr(particle, name)
                for name in ("offset", "a", "b", "c"):
                    for axis, value in zip("xyz", getattr(particle, name), strict=True):
                        values[f"particle{index}.{name}.{axis}"] = value
                values[f"part{index}.translucency"] = part.translucency
                values[f"part{index}.scale"] = part.gfxobj_scale.x
                for axis, value in zip("xyz", part.frame.origin, strict=True):
                    values[f"part{index}.origin.{axis}"] = value
                values[f"part{index}.qw"] = part.frame.qw
            not_f32 = {name: value for name, value in values.items() if not is_f32(value)}
            assert not_f32 == {}
            # The doubles stay doubles: lifespans are rolled in doubles (acclient.h:52455).
            assert not all(is_f32(emitter.particles[i].lifespan) for i, _ in emitter.live_particles())
        finally:
            unregister_emitter_info(EMITTER_INFO)
