"""Animations and motion tables read from a portal DAT (acphys.dat.motion) and used by scenarios.

The records are laid out by tests/dat_support.py from the documented layout, independently of
the reader.
"""

from __future__ import annotations

import itertools
import struct
from pathlib import Path

import pytest
from tests.dat_support import (
    REGION_ID,
    SETUP_ID,
    animation_record,
    f32,
    frame_bytes,
    hook_bytes,
    motion_data_bytes,
    motion_table_record,
    region_record,
    setup_record,
    simple_dat,
)

import acphys
from acphys.dat import DatError, DatFile
from acphys.dat.motion import unpack_animation, unpack_motion_table
from acphys.motion import anim_hooks as hooks
from acphys.motion import commands as cmd
from acphys.motion.animation import Animation
from acphys.motion.motion_table import CLEARS_MODIFIERS, cycle_key
from support import step_records

TABLE_ID = 0x09000001  # the id setup_record names as default_mtable_id
READY_ANIM = 0x03000010
WALK_ANIM = 0x03000011
LINK_ANIM = 0x03000012
STEP = 3.12 / 30.0  # the walk animation's root motion per frame
NC = cmd.NON_COMBAT


def walk_hooks() -> list[bytes]:
    """Frame 15's hooks: SoundTweaked, two ReplaceObjects (short and long id), AnimDone, SetOmega."""
    return [
        hook_bytes(0x15, 1, struct.pack("<I3f", 0x0A000001, 0.5, 0.25, 0.75)),
        hook_bytes(0x5, 0, struct.pack("<BH", 5, 0x0123)),
        hook_bytes(0x5, -1, struct.pack("<BHH", 1, 0x8001, 0x2345)),
        hook_bytes(0x4, -1),
        hook_bytes(0x16, 0, struct.pack("<3f", 0.0, 0.0, 1.5)),
    ]


def walk_record() -> bytes:
    parts = [
        [frame_bytes((0.0, 0.0, 0.1 * i)), frame_bytes((0.5, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))]
        for i in range(30)
    ]
    pos = [frame_bytes((0.0, STEP, 0.0)) for _ in range(30)]
    return animation_record(WALK_ANIM, parts, pos, hooks={15: walk_hooks()})


def plain_record(anim_id: int, frames: int) -> bytes:
    return animation_record(anim_id, [[frame_bytes(), frame_bytes()] for _ in range(frames)])


def table_record() -> bytes:
    return motion_table_record(
        TABLE_ID,
        NC,
        {NC: cmd.READY},
        cycles=[
            motion_data_bytes(cycle_key(NC, cmd.READY), [(READY_ANIM, 0, -1, 30.0)]),
            motion_data_bytes(cycle_key(NC, cmd.WALK_FORWARD), [(WALK_ANIM, 0, -1, 30.0)], CLEARS_MODIFIERS),
        ],
        modifiers=[
            motion_data_bytes(cycle_key(NC, cmd.TURN_RIGHT), [], 0, (0.25, 0.0, 0.0), (0.0, 0.0, -1.5)),
        ],
        links={cycle_key(NC, cmd.READY): [motion_data_bytes(cmd.WALK_FORWARD, [(LINK_ANIM, 1, 3, 45.0)])]},
    )


def portal_records() -> dict[int, bytes]:
    return {
        SETUP_ID: setup_record(),
        REGION_ID: region_record(),
        TABLE_ID: table_record(),
        READY_ANIM: plain_record(READY_ANIM, 2),
        WALK_ANIM: walk_record(),
        LINK_ANIM: plain_record(LINK_ANIM, 4),
    }


# -- animations -------------------------------------------------------------------------------


def test_an_animation_reads_every_field() -> None:
    anim = unpack_animation(walk_record())
    assert anim.name == "0x03000011" and (anim.num_frames, anim.num_parts) == (30, 2)
    # bitfield bit 0: one position frame per frame after the counts (acclient.c:334085)
    assert anim.pos_frames is not None and len(anim.pos_frames) == 30
    assert all(f.origin.exactly_equals(acphys.Vector3(0.0, f32(STEP), 0.0)) for f in anim.pos_frames)
    # per frame: num_parts AFrames (origin, qw qx qy qz), then the hooks (acclient.c:333869)
    frame = anim.part_frames[7]
    assert frame.frames[0].origin.z == f32(0.7) and frame.frames[0].qw == 1.0
    assert frame.frames[1].origin.x == 0.5 and (frame.frames[1].qw, frame.frames[1].qz) == (0.0, 1.0)
    assert all(not f.hooks for i, f in enumerate(anim.part_frames) if i != 15)
    found = anim.part_frames[15].hooks
    # AnimDone (4) has no case in CAnimHook::UnPackHook: no hook is built (acclient.c:342736)
    assert [type(h) for h in found] == [
        hooks.SoundTweakedHook,
        hooks.ReplaceObjectHook,
        hooks.ReplaceObjectHook,
        hooks.SetOmegaHook,
    ]
    sound, short, long_, omega = found
    # SoundTweakedHook::UnPack: gid, then prob, prio, vol (acclient.c:343122)
    assert (sound.gid, sound.prob, sound.prio, sound.vol, sound.direction) == (0x0A000001, 0.5, 0.25, 0.75, 1)
    # AnimPartChange::UnPack: a byte part index, then a packed GfxObj id (acclient.c:471698)
    assert (short.part_index, short.part_id, short.direction) == (5, 0x01000123, 0)
    assert (long_.part_index, long_.part_id, long_.direction) == (1, 0x01012345, -1)
    # the hook after a 3- and a 5-byte body starts dword-aligned (ALIGN_PTR, acclient.c:342736)
    assert omega.axis.exactly_equals(acphys.Vector3(0.0, 0.0, 1.5)) and omega.direction == 0


def test_an_animation_without_bit_0_has_no_position_frames() -> None:
    # bit 1 (has hooks) only sets has_hooks; it does not change the layout (acclient.c:334085)
    anim = unpack_animation(animation_record(READY_ANIM, [[frame_bytes()]] * 3, flags=2))
    assert anim.pos_frames is None and anim.num_frames == 3 and anim.num_parts == 1


@pytest.mark.parametrize(
    ("kind", "body", "cls", "fields"),
    [
        (0x1, struct.pack("<I", 0x0A000002), hooks.SoundHook, {"gid": 0x0A000002}),
        (0x3, struct.pack("<i6f", 2, 1, 2, 3, 4, 5, 6), hooks.AttackHook,
         {"part_index": 2, "left": (1.0, 2.0), "right": (3.0, 4.0), "radius": 5.0, "height": 6.0}),
        (0x6, struct.pack("<I", 1), hooks.EtherealHook, {"ethereal": True}),
        (0x9, struct.pack("<I3f", 3, 0.5, 1.0, 2.0), hooks.LuminousPartHook,
         {"part": 3, "start": 0.5, "end": 1.0, "time": 2.0}),
        (0xC, struct.pack("<2f", 2.0, 0.5), hooks.ScaleHook, {"end": 2.0, "time": 0.5}),
        (0xD, struct.pack("<II7fI", 0x32000001, 1, 0, 0, 1, 1, 0, 0, 0, 9), hooks.CreateParticleHook,
         {"emitter_info_id": 0x32000001, "part_index": 1, "emitter_id": 9}),
        (0x11, b"", hooks.DefaultScriptHook, {}),
        (0x13, struct.pack("<If", 0x33000001, 0.25), hooks.CallPESHook, {"pes": 0x33000001, "pause": 0.25}),
        (0x14, struct.pack("<3f", 0.0, 1.0, 0.5), hooks.TransparentHook,
         {"start": 0.0, "end": 1.0, "time": 0.5}),
        (0x18, struct.pack("<i2f", 4, 0.5, 0.25), hooks.TextureVelocityPartHook,
         {"part_index": 4, "u_speed": 0.5, "v_speed": 0.25}),
    ],
)  # fmt: skip
def test_hook_kinds_read_their_fields(kind: int, body: bytes, cls: type, fields: dict[str, object]) -> None:
    # each kind's UnPack (acclient.c:342736 switch); a SetOmega after it proves the length read
    record = animation_record(
        READY_ANIM,
        [[frame_bytes()]],
        hooks={0: [hook_bytes(kind, 1, body), hook_bytes(0x16, 0, struct.pack("<3f", 0, 0, 2.0))]},
    )
    found = unpack_animation(record).part_frames[0].hooks
    assert type(found[0]) is cls and found[0].direction == 1
    assert {name: getattr(found[0], name) for name in fields} == fields
    assert isinstance(found[1], hooks.SetOmegaHook) and found[1].axis.z == 2.0


def test_bad_animations_are_dat_errors() -> None:
    unknown = animation_record(READY_ANIM, [[frame_bytes()]], hooks={0: [hook_bytes(27, 0)]})
    with pytest.raises(DatError, match=r"animation 0x03000010: unknown animation hook type 27"):
        unpack_animation(unknown)
    bad_direction = animation_record(READY_ANIM, [[frame_bytes()]], hooks={0: [hook_bytes(0x11, 5)]})
    with pytest.raises(DatError, match=r"hook type 17: .*direction"):
        unpack_animation(bad_direction)
    with pytest.raises(DatError, match=r"animation 0x03000011: record truncated"):
        unpack_animation(walk_record()[:-10])
    with pytest.raises(DatError, match=r"has no frames"):
        unpack_animation(animation_record(READY_ANIM, []))


# -- motion tables ----------------------------------------------------------------------------


def test_a_motion_table_reads_every_field(tmp_path: Path) -> None:
    path = simple_dat(tmp_path, portal_records())
    loaded: dict[int, Animation] = {}

    with DatFile(path) as dat:

        def load(anim_id: int) -> Animation:
            if anim_id not in loaded:
                loaded[anim_id] = unpack_animation(dat.read(anim_id))
            return loaded[anim_id]

        table = unpack_motion_table(dat.read(TABLE_ID), load)
    # default style, style defaults, cycles, modifiers, links (acclient.c:338603)
    assert table.default_style == NC and table.style_defaults == {NC: cmd.READY}
    assert sorted(table.cycles) == sorted([cycle_key(NC, cmd.READY), cycle_key(NC, cmd.WALK_FORWARD)])
    walk = table.cycles[cycle_key(NC, cmd.WALK_FORWARD)]
    # MotionData: anims, bitfield, no vector flags -> zero velocity and omega (acclient.c:341813)
    assert walk.bitfield == CLEARS_MODIFIERS and walk.num_anims == 1
    assert walk.velocity.exactly_equals(acphys.Vector3()) and walk.omega.exactly_equals(acphys.Vector3())
    anim = walk.anims[0]
    # AnimData: anim id, low frame, high frame, framerate (acclient.c:341178)
    assert anim.animation is loaded[WALK_ANIM] and (anim.low_frame, anim.high_frame, anim.framerate) == (
        0,
        -1,
        30.0,
    )
    ready = table.cycles[cycle_key(NC, cmd.READY)].anims[0]
    assert ready.animation is loaded[READY_ANIM] and ready.animation.num_frames == 2
    turn = table.modifiers[cycle_key(NC, cmd.TURN_RIGHT)]
    # flag bit 0: velocity, bit 1: omega, after the (here no) animations (acclient.c:341813)
    assert turn.num_anims == 0 and turn.bitfield == 0
    assert turn.velocity.exactly_equals(acphys.Vector3(0.25, 0.0, 0.0))
    assert turn.omega.exactly_equals(acphys.Vector3(0.0, 0.0, -1.5))
    assert list(table.links) == [cycle_key(NC, cmd.READY)]
    link = table.links[cycle_key(NC, cmd.READY)][cmd.WALK_FORWARD]
    assert link.anims[0].animation is loaded[LINK_ANIM]
    assert (link.anims[0].low_frame, link.anims[0].high_frame, link.anims[0].framerate) == (1, 3, 45.0)


def test_a_repeated_cycle_key_keeps_the_last() -> None:
    anims = {READY_ANIM: unpack_animation(plain_record(READY_ANIM, 2))}
    key = cycle_key(NC, cmd.READY)
    record = motion_table_record(
        TABLE_ID,
        NC,
        {},
        [motion_data_bytes(key, [], 1), motion_data_bytes(key, [(READY_ANIM, 0, -1, 10.0)], 2)],
    )
    # each MotionData goes to the front of its hash bucket; lookups find the newest (acclient.c:338603)
    table = unpack_motion_table(record, anims.__getitem__)
    assert table.cycles[key].bitfield == 2 and table.cycles[key].anims[0].framerate == 10.0


def test_a_truncated_motion_table_is_a_dat_error() -> None:
    with pytest.raises(DatError, match=r"motion table 0x09000001: record truncated"):
        unpack_motion_table(table_record()[:-8], lambda anim_id: unpack_animation(plain_record(anim_id, 2)))


# -- scenarios --------------------------------------------------------------------------------

WALK = """[data]
portal = "client_portal.dat"

[[landblock]]
id = "0xA9B4"
height = 50.0

[[body]]
name = "walker"
landblock = "0xA9B4"
origin = [80.0, 60.0, 50.0]
on_ground = true
{extra}
[[event]]
at = 0.5
body = "walker"
action = "motion"
motion = "WalkForward"
"""


def load(folder: Path, text: str) -> acphys.Simulation:
    path = folder / "world.toml"
    path.write_text(text, encoding="utf-8")
    return acphys.load_scenario(path)


def walked_steps(sim: acphys.Simulation, trace: Path) -> list[float]:
    sim.run(until=2.5, trace=trace)
    ys = [record["origin"][1] for record in step_records(trace)]
    return [(b - a) / f32(STEP) for a, b in itertools.pairwise(ys)]


def test_the_human_takes_the_setups_motion_table_and_walks_its_root_motion(tmp_path: Path) -> None:
    simple_dat(tmp_path, portal_records())
    sim = load(tmp_path, WALK.format(extra=""))
    table = sim.body("walker").part_array.setup.motion_table
    assert table is not None and cycle_key(NC, cmd.WALK_FORWARD) in table.cycles
    assert table.cycles[cycle_key(NC, cmd.WALK_FORWARD)].anims[0].animation.name == "0x03000011"
    steps = walked_steps(sim, tmp_path / "walk.jsonl")
    # every move is whole walk frames of 3.12/30 m (one position frame per frame boundary,
    # CSequence::apply_physics / update_internal); the MotionData has no velocity of its own
    assert all(abs(s - round(s)) < 1e-4 and round(s) in (0, 1, 2) for s in steps)
    assert sum(round(s) for s in steps) >= 55  # 30 frames a second from 0.5 s (after the link)


def test_a_dat_motion_table_id_on_a_setup_or_body(tmp_path: Path) -> None:
    records = portal_records()
    records[0x02000123] = setup_record(setup_id=0x02000123)
    simple_dat(tmp_path, records)
    rock = "\n[setup.rock]\nspheres = [{ center = [0.0, 0.0, 0.5], radius = 0.5 }]\n"
    rock += 'motion_table = "0x09000001"\n'
    sim = load(tmp_path, WALK.format(extra='setup = "rock"\n') + rock)
    assert sim.body("walker").part_array.setup.motion_table.default_style == NC
    steps = walked_steps(sim, tmp_path / "rock.jsonl")
    assert sum(round(s) for s in steps) >= 55
    sim = load(tmp_path, WALK.format(extra='setup = "0x02000123"\nmotion_table = "0x09000001"\n'))
    assert sim.body("walker").movement_manager is not None


def test_dat_motion_table_errors(tmp_path: Path) -> None:
    simple_dat(tmp_path, portal_records())
    with pytest.raises(acphys.ScenarioError, match=r"motion_table: 0x02000001 is not a motion table"):
        load(tmp_path, WALK.format(extra='motion_table = "0x02000001"\n'))
    with pytest.raises(acphys.ScenarioError, match=r"body\[0\]\.motion_table: no motion table 0x09000002"):
        load(tmp_path, WALK.format(extra='motion_table = "0x09000002"\n'))
    no_data = WALK.split("\n", 3)[3].format(extra='motion_table = "0x09000001"\n')
    with pytest.raises(acphys.ScenarioError, match=r"body\[0\]\.motion_table: .*needs a \[data\] portal"):
        load(tmp_path, no_data)
    records = portal_records()
    del records[LINK_ANIM]
    simple_dat(tmp_path, records)
    # the human's table is read with its setup: the error names the setup key
    missing = r"motion table 0x09000001: no animation 0x03000012 \(line \d+, body 'walker'\)$"
    with pytest.raises(acphys.ScenarioError, match=r"body\[0\]\.setup: .*: " + missing):
        load(tmp_path, WALK.format(extra=""))
