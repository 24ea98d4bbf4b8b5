"""The DAT reader's limits (issue 13): every damaged or hostile DAT is one DatError line naming the
file and the offset or record, within seconds and well under 1 GB, never a RecursionError, a
hang or gigabytes: directories 3,000 nodes deep or looping, records that inflate a thousandfold
or declare sizes no file holds, block chains that leave the file, FIFOs and devices, and record
values (non-finite floats, coordinates, quaternions, framerates) that would stall the engine.

Every DAT is built here in ``tmp_path`` from the documented layout (``tests/dat_support.py``);
the command line runs as a subprocess under a 1 GiB address-space limit and a timeout.
"""

from __future__ import annotations

import os
import resource
import struct
import subprocess
import sys
import zlib
from pathlib import Path

import pytest

from acphys.cli import main
from acphys.dat import DatError, DatFile, unpack_setup
from acphys.dat.container import DATA_START, MAX_DIRECTORY_DEPTH, MAX_RECORD_SIZE, MIN_BLOCK_SIZE
from acphys.dat.env_cell import make_env_cell, unpack_env_cell, unpack_environment
from acphys.dat.gfxobj import unpack_gfxobj
from acphys.dat.landblock_info import unpack_landblock_info
from acphys.dat.motion import MAX_FRAMERATE, unpack_animation, unpack_motion_table
from acphys.dat.records import MAX_COORDINATE, MAX_QUATERNION_NORM2
from dat_support import (
    BLOCK,
    BOX_GFXOBJ_ID,
    BOX_SETUP_ID,
    CELL,
    LANDBLOCK_ID,
    LANDBLOCK_INFO_ID,
    REGION_ID,
    SETUP_ID,
    Writer,
    animation_record,
    bld_portal_bytes,
    box_gfxobj_record,
    box_setup_record,
    build_info_bytes,
    cell_portal_bytes,
    env_cell_record,
    environment_record,
    frame_bytes,
    landblock_info_record,
    landblock_record,
    motion_data_bytes,
    motion_table_record,
    region_record,
    setup_record,
    simple_dat,
    stab_bytes,
)

#: The memory the command line may use: the issue's bound.
MEMORY_LIMIT = 1 << 30
#: The seconds a command may take before the test fails (the issue allows 30).
TIME_LIMIT = 30


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def _acphys(*args: str | Path, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``acphys ARGS`` in a subprocess limited to :data:`MEMORY_LIMIT` and :data:`TIME_LIMIT`."""
    return subprocess.run(
        [sys.executable, "-m", "acphys.cli", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=TIME_LIMIT,
        preexec_fn=_limit_memory,
    )


def _one_error_line(done: subprocess.CompletedProcess[str], *parts: str | Path) -> str:
    """The single ``acphys: error:`` line of a run that exited 2, holding every one of ``parts``."""
    lines = done.stderr.splitlines()
    assert done.returncode == 2, done.stderr
    assert len(lines) == 1 and lines[0].startswith("acphys: error: "), lines
    for part in parts:
        assert str(part) in lines[0], lines[0]
    assert "internal error" not in lines[0]
    return lines[0]


def _expect(path: Path, match: str, action: str = "read", object_id: int = SETUP_ID) -> DatError:
    """Open ``path`` and list it (``action`` "list"), look ``object_id`` up ("lookup") or read it
    ("read"): a DatError matching ``match`` that names the file."""
    with pytest.raises(DatError, match=match) as caught, DatFile(path) as dat:
        if action == "list":
            list(dat.entries())
        elif action == "lookup":
            dat.lookup(object_id)
        else:
            dat.read(object_id)
    message = str(caught.value)
    assert str(path) in message and "\n" not in message
    return caught.value


# -- directories ------------------------------------------------------------------------------

#: The one record of a chain directory, in its deepest node.
CHAIN_ID = 0x0A010000


def _chain_dat(path: Path, depth: int) -> tuple[Path, list[int]]:
    """A directory that is a chain of ``depth`` nodes: each but the last has no entries and one
    child (child 0: the next, deeper node); the last is a leaf holding record ``CHAIN_ID``.
    Returns the file and the node offsets, root first."""
    writer = Writer()
    leaf = writer.store(Writer.node([0], [writer.entry(CHAIN_ID, b"chain record")]))
    offsets = [leaf]
    for _ in range(depth - 1):  # upwards: each parent needs its child's offset
        offsets.append(writer.store(Writer.node([offsets[-1]], [])))
    return writer.write(path, offsets[-1]), offsets[::-1]


def _patch(path: Path, offset: int, value: int) -> None:
    """Overwrite the dword at file ``offset``."""
    image = bytearray(path.read_bytes())
    struct.pack_into("<I", image, offset, value)
    path.write_bytes(bytes(image))


def test_a_3000_deep_directory_is_one_line_from_info_and_list(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The issue's case: a B-tree that is a 3,000-node chain was a RecursionError (exit 3)."""
    path, offsets = _chain_dat(tmp_path / "deep.dat", 3000)
    last = offsets[MAX_DIRECTORY_DEPTH - 1]  # the deepest node read
    expected = f"{path} at offset {last:#x}: directory deeper than {MAX_DIRECTORY_DEPTH} levels"
    _one_error_line(_acphys("dat", "info", path, cwd=tmp_path), expected, "MAX_DIRECTORY_DEPTH")
    assert main(["dat", "list", str(path)]) == 2
    assert capsys.readouterr().err.splitlines() == [
        f"acphys: error: {expected} (MAX_DIRECTORY_DEPTH): node {last:#x} at depth "
        f"{MAX_DIRECTORY_DEPTH} has children"
    ]


def test_a_directory_as_deep_as_the_limit_reads_and_one_deeper_does_not(tmp_path: Path) -> None:
    path, _ = _chain_dat(tmp_path / "limit.dat", MAX_DIRECTORY_DEPTH)
    with DatFile(path) as dat:
        assert list(dat.ids()) == [CHAIN_ID]
        assert dat.read(CHAIN_ID) == b"chain record"
    path, _ = _chain_dat(tmp_path / "over.dat", MAX_DIRECTORY_DEPTH + 1)
    for action in ("list", "lookup"):
        _expect(path, f"directory deeper than {MAX_DIRECTORY_DEPTH} levels", action, CHAIN_ID)


@pytest.mark.parametrize("target", ["itself", "the root"])
def test_a_directory_that_loops_is_refused(tmp_path: Path, target: str) -> None:
    """A node naming itself or an ancestor: the walk and the lookup reach each node once, so
    neither goes round forever."""
    path, offsets = _chain_dat(tmp_path / "loop.dat", 4)
    looped = offsets[2] if target == "itself" else offsets[0]
    _patch(path, offsets[2] + 4, looped)  # the third node's child 0, its first payload dword
    for action in ("list", "lookup"):
        error = _expect(path, "loop in the directory", action, CHAIN_ID)
        assert f"node {offsets[2]:#x} names node {looped:#x} (child 0), which is reached twice" in str(error)


def test_a_node_two_parents_name_is_refused(tmp_path: Path) -> None:
    """A node named twice (here both children of the root) would be listed twice, and a tree of
    such nodes would list 62 to the power of its depth entries."""
    writer = Writer()
    leaf = writer.store(Writer.node([0], [writer.entry(0x0A000001, b"a")]))
    root = writer.store(Writer.node([leaf, leaf], [writer.entry(0x0A000002, b"b")]))
    path = writer.write(tmp_path / "shared.dat", root)
    _expect(path, f"node {root:#x} names node {leaf:#x} \\(child 1\\), which is reached twice", "list")


def test_a_directory_of_more_nodes_than_the_file_holds_is_refused(tmp_path: Path) -> None:
    """A root naming 62 children in a run of zero bytes: each reads as an empty leaf, at offsets
    4 bytes apart, so the file's 6 KB hold "nodes" of 1,716 bytes dozens of times over."""
    writer = Writer(2048)
    zeros = writer.alloc()
    writer.alloc()  # 4 KB of zero blocks: every offset in the first 2 KB reads as a whole node
    entries = [(0, 0x0A000000 + i, zeros, 4, 0, 0) for i in range(61)]
    root = writer.store(Writer.node([zeros + 4 * i for i in range(62)], entries))
    path = writer.write(tmp_path / "many.dat", root)
    limit = path.stat().st_size // 1716
    _expect(path, f"directory has more than the {limit} nodes of 1716 bytes a file of", "list")


@pytest.mark.parametrize(
    ("root", "match"),
    [
        (0, "the directory root is at 0x0, inside the header"),
        (0x200, "the directory root is at 0x200, inside the header"),
        (0x7FFFFF00, "file truncated: the directory root is at 0x7fffff00, past its end"),
    ],
)
def test_a_directory_root_outside_the_data_is_refused(tmp_path: Path, root: int, match: str) -> None:
    path = simple_dat(tmp_path)
    _patch(path, 0x140 + 8 * 4, root)  # DiskFileInfo_t.btree_root, the ninth dword
    with pytest.raises(DatError, match=f"{path} at offset 0x140: {match}"):
        DatFile(path)


def test_a_child_outside_the_data_is_refused(tmp_path: Path) -> None:
    path, offsets = _chain_dat(tmp_path / "child.dat", 3)
    _patch(path, offsets[1] + 4, 0x10)  # the second node's child 0: into the header
    _expect(path, f"child 0 of directory node {offsets[1]:#x} is at 0x10, inside the header", "list")
    _patch(path, offsets[1] + 4, 0x7FFFFF00)
    _expect(
        path,
        "file truncated: child 0 of directory node .* is at 0x7fffff00, past its end",
        "lookup",
        CHAIN_ID,
    )


def test_a_block_size_under_the_minimum_is_refused(tmp_path: Path) -> None:
    path = simple_dat(tmp_path)
    _patch(path, 0x140 + 4, MIN_BLOCK_SIZE - 1)
    with pytest.raises(DatError, match=f"bad block size {MIN_BLOCK_SIZE - 1} \\(under {MIN_BLOCK_SIZE}"):
        DatFile(path)


# -- block chains and declared sizes ----------------------------------------------------------


def _one_record_dat(path: Path, data: bytes, compressed: bool = False, size: int | None = None) -> Path:
    """A one-node DAT holding ``data`` as SETUP_ID (its entry's size ``size`` if given)."""
    writer = Writer()
    first = writer.store(data)
    entry = (int(compressed), SETUP_ID, first, len(data) if size is None else size, 0, 0)
    return writer.write(path, writer.store(Writer.node([0], [entry])))


@pytest.mark.parametrize(
    ("link", "match"),
    [
        (0x10, "block chain reaches block 0x10, inside the header"),
        (0x7FFFFFF0, "file truncated: the block chain reaches block 0x7ffffff0, the file ends at"),
        (0x80000400, "block chain reaches a free block after block 0x500"),
        (DATA_START, "loop in the block chain: block 0x400 comes round again"),
    ],
)
def test_a_block_link_out_of_the_chain_is_refused(tmp_path: Path, link: int, match: str) -> None:
    path = _one_record_dat(tmp_path / "link.dat", b"x" * 600)  # three blocks from 0x400
    _patch(path, DATA_START + BLOCK, link)  # the second block's link
    error = _expect(path, match)
    assert f"at offset 0x400: record {SETUP_ID:#010x}: " in str(error)


def test_declared_sizes_are_bounded_by_the_limit_and_the_file(tmp_path: Path) -> None:
    path = _one_record_dat(tmp_path / "huge.dat", b"x" * 100, size=0xFFFFFFFF)
    _expect(path, f"record 0x02000001 is 4294967295 bytes, over the {MAX_RECORD_SIZE}-byte limit")
    path = _one_record_dat(tmp_path / "big.dat", b"x" * 100, size=1_000_000)
    _expect(path, "record 0x02000001: 1000000 bytes, more than the whole file")


def _compressed(plain_size: int, stream: bytes) -> bytes:
    return struct.pack("<I", plain_size) + stream


def test_a_record_that_inflates_past_what_it_declares_stops_at_the_declared_size(tmp_path: Path) -> None:
    record = region_record()
    stream = zlib.compress(record + bytes(100_000))
    path = _one_record_dat(tmp_path / "more.dat", _compressed(len(record), stream), compressed=True)
    _expect(path, f"record 0x02000001 decompresses to more than the {len(record)} bytes it declares")
    path = _one_record_dat(tmp_path / "less.dat", _compressed(len(record) + 1, zlib.compress(record)), True)
    _expect(path, f"decompresses to {len(record)} bytes, not {len(record) + 1}")
    cut = zlib.compress(record)[:-10]
    path = _one_record_dat(tmp_path / "cut.dat", _compressed(len(record), cut), compressed=True)
    _expect(path, "does not decompress: its zlib stream ends early")
    path = _one_record_dat(tmp_path / "limit.dat", _compressed(MAX_RECORD_SIZE + 1, stream), True)
    _expect(path, f"declares {MAX_RECORD_SIZE + 1} bytes uncompressed, over the {MAX_RECORD_SIZE}-byte")


#: The issue's zip bomb: a region record followed by 1,430 MiB of zeros, 1.5 GB in all.
BOMB_MIB = 1430


def _bomb_stream(head: bytes) -> bytes:
    """A zlib stream of ``head`` then :data:`BOMB_MIB` MiB of zeros, made without compressing
    them: after a full flush, deflate starts afresh, so each MiB of zeros compresses to the same
    byte-aligned segment, repeated; the final block and the checksum close the stream (Adler-32
    over zeros: the sum ``a`` stays, ``b`` gains ``a`` a byte)."""
    compressor = zlib.compressobj(9)
    start = compressor.compress(head) + compressor.flush(zlib.Z_FULL_FLUSH)
    segment = compressor.compress(bytes(1 << 20)) + compressor.flush(zlib.Z_FULL_FLUSH)
    checksum = zlib.adler32(head)
    low, high = checksum & 0xFFFF, checksum >> 16
    checksum = (high + (BOMB_MIB << 20) * low) % 65521 << 16 | low
    end = compressor.flush()[:-4] + struct.pack(">I", checksum)
    return start + segment * BOMB_MIB + end


@pytest.mark.parametrize("declared", ["its head", "all of it"])
def test_a_small_dat_whose_record_inflates_to_gigabytes_is_refused_at_once(
    tmp_path: Path, declared: str
) -> None:
    """The issue's case: ``dat heights`` on a 1.6 MB DAT whose region record inflates to 1.5 GB
    reached 3 GB before it refused; now the inflating stops at the declared size (plus one
    byte), and a declared size over the record limit is refused before any."""
    head = region_record()
    plain_size = len(head) + (BOMB_MIB << 20)
    size = len(head) if declared == "its head" else plain_size
    stream = _bomb_stream(head)
    assert zlib.decompressobj().decompress(stream, 3 << 20)[: len(head)] == head
    data = struct.pack("<I", size) + stream
    writer = Writer(1024)
    entry = writer.entry(REGION_ID, data, bitfield=(2 << 16) | 1)
    path = writer.write(tmp_path / "bomb.dat", writer.store(Writer.node([0], [entry])))
    assert path.stat().st_size < 1_600_000
    done = _acphys("dat", "heights", path, cwd=tmp_path)
    if declared == "its head":
        _one_error_line(done, path, f"decompresses to more than the {len(head)} bytes it declares")
    else:
        _one_error_line(done, path, f"declares {plain_size} bytes uncompressed", "MAX_RECORD_SIZE")


# -- files that are not files -----------------------------------------------------------------


def test_a_fifo_a_device_or_a_directory_is_refused_before_it_is_read(tmp_path: Path) -> None:
    """A FIFO blocked ``dat info`` forever (nothing writes to it): run as a subprocess, so that
    a regression fails on the timeout; /dev/zero never ends."""
    fifo = tmp_path / "portal.fifo"
    os.mkfifo(fifo)
    _one_error_line(_acphys("dat", "info", fifo, cwd=tmp_path), f"{fifo}: not a regular file (a FIFO)")
    cases = [(tmp_path, "a directory")]
    if Path("/dev/zero").exists():
        cases.append((Path("/dev/zero"), "a character device"))
    for path, kind in cases:
        with pytest.raises(DatError, match=f"^{path}: not a regular file \\({kind}\\)"):
            DatFile(path)
    with pytest.raises(DatError, match="a path cannot hold a NUL byte"):
        DatFile(tmp_path / "a\0b.dat")


def test_a_fifo_named_as_a_scenarios_portal_is_refused(tmp_path: Path) -> None:
    fifo = tmp_path / "client_portal.dat"
    os.mkfifo(fifo)
    scenario = tmp_path / "world.toml"
    scenario.write_text('[data]\nportal = "client_portal.dat"\n', encoding="utf-8")
    done = _acphys("check", scenario, cwd=tmp_path)
    _one_error_line(done, "data.portal", f"{fifo}: not a regular file (a FIFO)")


# -- record values that would stall the engine ------------------------------------------------


def _with(data: bytes, offset: int, fmt: str, *values: float) -> bytes:
    raw = bytearray(data)
    struct.pack_into(fmt, raw, offset, *values)
    return bytes(raw)


#: Byte offsets in ``setup_record()``: the first sphere's radius (0.48, its first such float) and
#: centre.
SETUP_SPHERE_RADIUS = setup_record().index(struct.pack("<f", 0.48))
SETUP_SPHERE_CENTER = SETUP_SPHERE_RADIUS - 12


def test_a_float_that_is_not_finite_is_refused() -> None:
    assert unpack_setup(setup_record()).spheres[0].radius == pytest.approx(0.48)
    for bad in (float("nan"), float("inf"), float("-inf")):
        with pytest.raises(
            DatError, match=f"setup 0x02000001: the values at byte {SETUP_SPHERE_RADIUS} hold"
        ):
            unpack_setup(_with(setup_record(), SETUP_SPHERE_RADIUS, "<f", bad))


def test_a_coordinate_beyond_the_limit_is_refused() -> None:
    data = _with(setup_record(), SETUP_SPHERE_CENTER, "<f", 2 * MAX_COORDINATE)
    with pytest.raises(DatError, match=f"hold 20000, beyond the {MAX_COORDINATE:g} m .*MAX_COORDINATE"):
        unpack_setup(data)
    # the box GfxObj's vertex 2 (DID, flags, 1-byte count, a surface id, vertex type and count,
    # then 36 bytes a vertex: id, UV count, position, normal, one UV)
    gfxobj = box_gfxobj_record((-1.0, -1.0, 0.0), (1.0, 1.0, 2.0))
    vertex = 4 + 4 + 1 + 4 + 8 + 2 * 36 + 4
    assert unpack_gfxobj(gfxobj).vertices[2].x == -1.0
    with pytest.raises(
        DatError, match=f"gfxobj 0x01000010: the coordinates at byte {vertex} hold -1.7e\\+38"
    ):
        unpack_gfxobj(_with(gfxobj, vertex, "<f", -1.7e38))


def test_a_quaternion_that_is_no_rotation_is_refused() -> None:
    """A landblock info's object whose quaternion's exponent is damaged (qz 5e7) would stretch
    its box over the whole map: placing it never finished."""
    good = landblock_info_record(objects=[stab_bytes(BOX_SETUP_ID, (20.0, 20.0, 0.0))])
    assert unpack_landblock_info(good).object_frames[0].qw == 1.0
    quaternion = 4 * 3 + 4 + 12  # DID, cells, objects; the object's DID, its origin
    bad = _with(good, quaternion + 12, "<f", 5e7)
    with pytest.raises(DatError, match=f"byte {quaternion} has squared norm 2.5e\\+15, over 2.0"):
        unpack_landblock_info(bad)
    # a rotation's squared norm is 1 to float32 rounding; a zero quaternion turns nothing
    assert MAX_QUATERNION_NORM2 == 2.0
    zero = _with(good, quaternion, "<4f", 0.0, 0.0, 0.0, 0.0)
    assert unpack_landblock_info(zero).object_frames[0].qw == 0.0


def test_a_framerate_over_the_limit_is_refused() -> None:
    """A walk cycle at 1e7 frames a second stalled the simulation (every frame is stepped)."""
    animation = unpack_animation(animation_record(0x03000011, [[frame_bytes()] for _ in range(3)]))
    for rate, ok in ((30.0, True), (-MAX_FRAMERATE, True), (1e7, False), (-3e38, False)):
        table = motion_table_record(
            0x09000001, 0x8000003D, {}, [motion_data_bytes(0x0003D0003, [(0x03000011, 0, -1, rate)])]
        )
        if ok:
            unpack_motion_table(table, lambda _anim_id: animation)
        else:
            with pytest.raises(DatError, match="frames a second, over 1000 \\(MAX_FRAMERATE\\)"):
                unpack_motion_table(table, lambda _anim_id: animation)


def test_portals_into_land_cells_are_dat_errors() -> None:
    """A building portal or an env cell portal naming a cell below 0x0100 (a land cell) was a
    ValueError from the world's portal classes (exit 3)."""
    door = bld_portal_bytes(0, 0x0005, 0, [0x0100])
    info = landblock_info_record(buildings=[build_info_bytes(0x01000020, (93.0, 93.0, 0.0), 1, [door])])
    with pytest.raises(
        DatError, match=r"building portal at byte \d+ leads into cell 0x0005, not an env cell"
    ):
        unpack_landblock_info(info)
    environment = unpack_environment(environment_record())
    cell = env_cell_record(0xA9B40100, (10.0, 10.0, 0.0), [cell_portal_bytes(0, 1, 0x00E4, 0)])
    with pytest.raises(DatError, match="env cell 0xa9b40100: portal 0: a cell portal leads to an env cell"):
        make_env_cell(unpack_env_cell(cell), environment, environment.to_environment())


def test_a_scenario_on_an_object_with_a_stretching_quaternion_fails_in_one_line(tmp_path: Path) -> None:
    """End to end, the case the fuzzing found: ``acphys check`` placing that object never ended."""
    simple_dat(
        tmp_path,
        {
            REGION_ID: region_record(),
            SETUP_ID: setup_record(),
            BOX_SETUP_ID: box_setup_record(),
            BOX_GFXOBJ_ID: box_gfxobj_record((-0.5, -0.5, 0.0), (0.5, 0.5, 1.0)),
        },
    )
    stretched = struct.pack("<I", BOX_SETUP_ID) + frame_bytes((20.0, 20.0, 0.0), (1.0, 0.0, 0.0, 5e7))
    cells = {
        LANDBLOCK_ID: landblock_record(terrain=[0] * 81, heights=[0] * 81),
        LANDBLOCK_INFO_ID: landblock_info_record(objects=[stretched]),
    }
    simple_dat(tmp_path, cells, name="client_cell_1.dat", data_set=CELL)
    scenario = tmp_path / "world.toml"
    scenario.write_text(
        '[data]\nportal = "client_portal.dat"\ncell = "client_cell_1.dat"\n\n[[landblock]]\nid = "0xA9B4"\n'
        '\n[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 0.0]\n',
        encoding="utf-8",
    )
    done = _acphys("check", scenario, cwd=tmp_path)
    _one_error_line(done, "landblock[0]", "client_cell_1.dat", "MAX_QUATERNION_NORM2")
