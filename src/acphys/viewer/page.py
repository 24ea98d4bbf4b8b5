"""The page: a JSON description and one binary blob, inlined into the HTML template.

The page holds two inline scripts the viewer reads, and nothing it loads from elsewhere:

- ``<script type="application/json" id="acphys-data">``: the description (:data:`FORMAT`): the
  title, notes, the scene frame, the time span, the scene (terrain per landblock, objects), the
  records (one array per column, every body's records one after another, ``widths`` values a
  record), the bodies (name, id, ``first`` record and ``records``, ``stride``, ``shape``: an
  index into ``shapes``), the events and the tables (transient flag names, motion states,
  event strings). Every array in it is a reference ``[dtype, byte offset, count]`` into the blob;
- ``<script type="application/octet-stream" id="acphys-blob">``: the arrays, little-endian,
  each at an offset a multiple of 8, the whole gzip-compressed and base64-encoded (the page
  inflates it with the browser's own ``DecompressionStream``).

:func:`read_page` reads both back (the tests use it).
"""

from __future__ import annotations

import base64
import gzip
import json
import re
from array import array
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from acphys.inputs import one_line
from acphys.viewer.records import COLUMNS, RecordCollector
from acphys.viewer.scene import Scene, block_offset

#: The description's format name.
FORMAT = "acphys.viewer/1"
#: Array types of the blob, by the name the description gives them.
DTYPES = {"f32": "<f4", "f64": "<f8", "u32": "<u4", "i32": "<i4", "u8": "u1"}
_TYPECODES = {"f": "f32", "d": "f64", "I": "u32", "i": "i32", "B": "u8"}
_DATA_TAG = '<script type="application/json" id="acphys-data">'
_BLOB_TAG = '<script type="application/octet-stream" id="acphys-blob">'


@dataclass
class BodyShape:
    """A body's spheres and cylinders in its own frame, scaled (x, y, z, r / x, y, z, r, h), and
    where they came from: ``setup`` (its setup's), ``sorting`` (its setup has neither: its
    sorting sphere) or ``unknown`` (no scenario: a 0.5-m marker)."""

    spheres: list[tuple[float, float, float, float]]
    cylinders: list[tuple[float, float, float, float, float]]
    source: str


UNKNOWN_SHAPE = BodyShape([(0.0, 0.0, 0.5, 0.5)], [], "unknown")


class Blob:
    """Arrays packed one after another (8-byte aligned), each named by a reference."""

    def __init__(self) -> None:
        self._parts: list[bytes] = []
        self._size = 0

    def add(self, values: Any, dtype: str) -> list[Any]:
        """Append ``values`` as ``dtype`` (a key of :data:`DTYPES`); returns the reference."""
        data = np.asarray(values, dtype=DTYPES[dtype]).ravel()
        raw = data.tobytes()
        ref = [dtype, self._size, int(data.size)]
        pad = (-len(raw)) % 8
        self._parts.append(raw + b"\0" * pad)
        self._size += len(raw) + pad
        return ref

    def add_array(self, values: array[Any]) -> list[Any]:
        return self.add(
            np.frombuffer(values, dtype=values.typecode) if len(values) else [], _TYPECODES[values.typecode]
        )

    def encode(self) -> str:
        """gzip (level 9, no timestamp: the same data gives the same page) then base64."""
        return base64.b64encode(gzip.compress(b"".join(self._parts), compresslevel=9, mtime=0)).decode(
            "ascii"
        )


def page_data(
    title: str,
    collector: RecordCollector,
    shapes: dict[str, BodyShape],
    scene: Scene | None,
    base: tuple[int, int],
    notes: list[str],
    source: dict[str, Any],
) -> tuple[dict[str, Any], Blob]:
    """The description and blob of a page."""
    blob = Blob()
    bodies = []
    shape_list: list[dict[str, Any]] = []
    shape_index: dict[str, int] = {}
    start, end = float("inf"), float("-inf")
    first = 0
    for body in collector.bodies.values():
        shape = shapes.get(body.name, UNKNOWN_SHAPE)
        described = {
            "source": shape.source,
            "spheres": [list(s) for s in shape.spheres],
            "cylinders": [list(c) for c in shape.cylinders],
        }
        key = json.dumps(described)
        if key not in shape_index:
            shape_index[key] = len(shape_list)
            shape_list.append(described)
        times = body.columns["t"]
        if times:
            start, end = min(start, times[0]), max(end, times[-1])
        bodies.append(
            {
                "name": body.name,
                "id": body.id,
                "first": first,
                "records": len(body),
                "stride": body.stride,
                "shape": shape_index[key],
            }
        )
        first += len(body)
    if start > end:
        start = end = 0.0
    columns = {}
    for name, code, _width in COLUMNS:
        joined: array[Any] = array(code)
        for body in collector.bodies.values():
            joined.extend(body.columns[name])
        columns[name] = blob.add_array(joined)
    events = collector.events
    origins = np.frombuffer(events.origin, dtype="f4").reshape(-1, 3).astype("f8") if len(events) else None
    positions = np.zeros((len(events), 3))
    if origins is not None:
        offsets = np.array([block_offset(cell, base) for cell in events.cell]).reshape(-1, 2)
        positions[:, :2] = origins[:, :2] + offsets
        positions[:, 2] = origins[:, 2]
    data: dict[str, Any] = {
        "format": FORMAT,
        "title": one_line(title),
        "source": source,
        "notes": notes,
        "base": {"landblock": f"0x{base[0]:02X}{base[1]:02X}", "x": base[0], "y": base[1]},
        "time": [start, end],
        "scene": _scene_data(scene, blob) if scene is not None else None,
        "records": {
            "count": first,
            "columns": columns,
            "widths": {name: width for name, _code, width in COLUMNS},
        },
        "shapes": shape_list,
        "bodies": bodies,
        "events": {
            "body": blob.add_array(events.body),
            "t": blob.add_array(events.t),
            "position": blob.add(positions, "f32"),
            "text": blob.add_array(events.text),
            "strings": events.strings,
        },
        "tables": {"transient": collector.transient_names, "motion": collector.motions},
    }
    return data, blob


def _scene_data(scene: Scene, blob: Blob) -> dict[str, Any]:
    return {
        "terrain": [
            {
                "landblock": f"0x{block.landblock:04X}",
                "x": block.x,
                "y": block.y,
                "heights": blob.add(block.heights, "f32"),
                "water": blob.add(block.water, "u8"),
                "cut": blob.add(block.cut, "u8"),
            }
            for block in scene.terrain
        ],
        "objects": [{"name": one_line(o.name), "kind": o.kind, "at": list(o.at)} for o in scene.objects],
        "solids": {"triangles": blob.add_array(scene.solids), "owner": blob.add_array(scene.solid_owner)},
        "shells": {"triangles": blob.add_array(scene.shells), "owner": blob.add_array(scene.shell_owner)},
        "rooms": {"triangles": blob.add_array(scene.rooms), "owner": blob.add_array(scene.room_owner)},
        "cylinders": {
            "values": blob.add_array(scene.cylinders),
            "owner": blob.add_array(scene.cylinder_owner),
        },
        "spheres": {"values": blob.add_array(scene.spheres), "owner": blob.add_array(scene.sphere_owner)},
    }


def _template(name: str) -> str:
    return resources.files("acphys.viewer").joinpath("template", name).read_text("utf-8")


def _script_safe(text: str) -> str:
    """JSON made safe inside a ``<script>``: no ``<``, ``>``, ``&`` nor line separators as such."""
    return (
        text.replace("<", "\\u003c")
        .replace(">", "\\u003e")
        .replace("&", "\\u0026")
        .replace("\u2028", "\\u2028")
        .replace("\u2029", "\\u2029")
    )


def render_html(data: dict[str, Any], blob: Blob) -> str:
    """The page: the template with its style, script, description and blob inlined."""
    page = _template("viewer.html")
    css, js = _template("viewer.css"), _template("viewer.js")
    for name, text in (("viewer.css", css), ("viewer.js", js)):
        if "</" in text.replace("<\\/", ""):  # pragma: no cover - a packaging mistake
            raise RuntimeError(f"{name} holds '</', which would end its inline element")
    description = _script_safe(json.dumps(data, allow_nan=False, separators=(",", ":")))
    title = data["title"].replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    replacements = {
        "{{TITLE}}": title,
        "{{CSS}}": css,
        "{{JS}}": js,
        "{{DATA}}": description,
        "{{BLOB}}": blob.encode(),
    }
    return re.sub(r"\{\{(TITLE|CSS|JS|DATA|BLOB)\}\}", lambda m: replacements[m.group(0)], page)


def read_page(html: str) -> tuple[dict[str, Any], bytes]:
    """The description and the (inflated) blob of a page :func:`render_html` wrote."""
    data_start = html.index(_DATA_TAG) + len(_DATA_TAG)
    data = json.loads(html[data_start : html.index("</script>", data_start)])
    blob_start = html.index(_BLOB_TAG) + len(_BLOB_TAG)
    blob = gzip.decompress(base64.b64decode(html[blob_start : html.index("</script>", blob_start)].strip()))
    return data, blob


def array_of(blob: bytes, ref: list[Any]) -> np.ndarray:
    """The array a reference names."""
    dtype, offset, count = ref
    return np.frombuffer(blob, dtype=DTYPES[dtype], count=count, offset=offset)


def body_columns(data: dict[str, Any], blob: bytes, body: dict[str, Any]) -> dict[str, np.ndarray]:
    """The columns of one body's records (a record a row for the columns of several values)."""
    records = data["records"]
    out = {}
    for name, ref in records["columns"].items():
        width = records["widths"][name]
        values = array_of(blob, ref)[body["first"] * width : (body["first"] + body["records"]) * width]
        out[name] = values.reshape(-1, width) if width > 1 else values
    return out
