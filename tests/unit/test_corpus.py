"""The conformance corpus (issue 15): ``acphys corpus export`` and ``acphys corpus check``.

The whole corpus is exported and checked once, through the command; everything else works on
two short cases. Nothing in acphys is mocked.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tomllib
from importlib import resources
from pathlib import Path

import pytest

import acphys
from acphys.cli import main
from acphys.corpus import CASES, MANIFEST, case_names, scenario_text
from acphys.scenario import build_scenario, builtin_scenarios, parse_scenario
from acphys.trace_diff import compare_traces
from engine_corpus import random_scenarios

#: Two short cases: a dart into a pillar (13 records) and a ball wedged in a pit (46).
SMALL = ("f32-dart", "ladder-11-pit")


def invoke(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Run ``main(argv)``: its exit code, then stdout (rich's wrapping and rules undone) and stderr."""
    code = main(argv)
    out, err = capsys.readouterr()
    return code, " ".join(out.replace("│", " ").split()), err


def one_error(code: int, err: str) -> str:
    """The single ``acphys: error:`` line of a command that exited 2."""
    assert code == 2, err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("acphys: error: "), err
    return lines[0]


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A corpus of the two short cases, exported once; tests change copies of it."""
    folder = tmp_path_factory.mktemp("corpus") / "small"
    assert main(["corpus", "export", str(folder), "--cases", ",".join(SMALL)]) == 0
    return folder


@pytest.fixture
def corpus(small: Path, tmp_path: Path) -> Path:
    return Path(shutil.copytree(small, tmp_path / "corpus"))


def _edit(trace: Path, key: str, value: object) -> None:
    """Set ``key`` of the last record of ``trace`` to ``value``."""
    lines = trace.read_text(encoding="utf-8").splitlines(keepends=True)
    record = json.loads(lines[-1])
    record[key] = value
    lines[-1] = json.dumps(record) + "\n"
    trace.write_text("".join(lines), encoding="utf-8")


def _edit_golden(corpus: Path, name: str, rehash: bool) -> None:
    """Move the last record of the golden trace of ``name`` by a millimetre, and with ``rehash``
    give the manifest the edited file's sha256."""
    golden = corpus / "golden" / f"{name}.jsonl"
    origin = json.loads(golden.read_text(encoding="utf-8").splitlines()[-1])["origin"]
    _edit(golden, "origin", [origin[0] + 0.001, *origin[1:]])
    if rehash:
        manifest = json.loads((corpus / MANIFEST).read_text(encoding="utf-8"))
        entry = next(case for case in manifest["cases"] if case["name"] == name)
        entry["golden"]["sha256"] = hashlib.sha256(golden.read_bytes()).hexdigest()
        (corpus / MANIFEST).write_text(json.dumps(manifest), encoding="utf-8")


def test_the_whole_corpus_exports_and_checks(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "corpus"
    code, out, _ = invoke(["corpus", "export", str(folder)], capsys)
    assert code == 0
    assert f"corpus: {len(CASES)} cases" in out
    code, out, err = invoke(["corpus", "check", str(folder)], capsys)
    assert code == 0, out
    assert f"{len(CASES)} passed, 0 failed" in out and not err
    manifest = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
    assert [case["name"] for case in manifest["cases"]] == case_names()
    assert manifest["format"] == "acphys.corpus/1" and manifest["acphys"] == acphys.__version__
    readme = (folder / "README.md").read_text(encoding="utf-8")
    for case in manifest["cases"]:
        assert f"| {case['name']} |" in readme
        assert case["records"] > 0 and case["bodies"] > 0 and 0 < case["until"] <= case["duration"]
        for key in ("scenario", "golden"):
            data = (folder / case[key]["path"]).read_bytes()
            assert hashlib.sha256(data).hexdigest() == case[key]["sha256"]


def test_the_corpus_covers_what_a_port_needs() -> None:
    groups = {case.group for case in CASES}
    assert groups == {"ladder", "locomotion", "managers", "arithmetic", "seams-and-doors", "random"}
    assert {f"ladder-{n:02d}" for n in range(1, 13)} <= {name[:9] for name in case_names()}
    assert len(set(case_names())) == len(CASES)


@pytest.mark.parametrize("name", case_names())
def test_every_case_has_a_scenario_that_loads(name: str) -> None:
    sim = parse_scenario(scenario_text(name), source=name)
    case = next(case for case in CASES if case.name == name)
    assert case.until is None or 0 < case.until < sim.duration


def test_every_corpus_file_is_a_case_and_none_shadows_a_built_in() -> None:
    folder = resources.files("acphys.data.corpus")
    files = {entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml")}
    assert files.isdisjoint(builtin_scenarios())
    assert files | set(builtin_scenarios()) >= set(case_names()) >= files


@pytest.mark.parametrize("seed", [0, 3, 5, 7])
def test_the_random_cases_are_the_generators_worlds(seed: int) -> None:
    text = scenario_text(f"random-{seed}")
    assert text.endswith(random_scenarios(seed))
    assert all(line.startswith("#") for line in text[: -len(random_scenarios(seed))].splitlines())


def test_an_exported_scenario_loads_and_runs_to_its_golden_trace(corpus: Path, tmp_path: Path) -> None:
    sim = acphys.load_scenario(corpus / "scenarios" / "f32-dart.toml")
    trace = tmp_path / "dart.jsonl"
    sim.run(trace=trace)
    assert trace.read_bytes() == (corpus / "golden" / "f32-dart.jsonl").read_bytes()


@pytest.mark.parametrize(("case", "until"), [("locomotion", 1.5), ("seam", 1.0)])
def test_the_builtins_pasted_into_a_scenario_run_the_same(
    case: str, until: float, small: Path, tmp_path: Path
) -> None:
    """The human setup, its motion table and the land height table, as the corpus writes them,
    given in the scenario itself instead of taken from acphys: the same trace, the animations'
    names (``motion.animation``, ``motion_table.humanoid.cycle[0]``, ...) included."""
    builtins = {
        name: tomllib.loads((small / "builtins" / f"{name}.toml").read_text(encoding="utf-8"))
        for name in ("human", "humanoid", "land_height_table")
    }
    document = tomllib.loads(scenario_text(case))
    document.setdefault("setup", {}).update(builtins["human"]["setup"])
    document.setdefault("motion_table", {}).update(builtins["humanoid"]["motion_table"])
    table = builtins["land_height_table"]["heights"]  # bytes 0-200; a height_table gives 256
    for landblock in document["landblock"]:
        if "heights" in landblock:
            landblock["height_table"] = table + [table[-1]] * (256 - len(table))
    pasted, built_in = tmp_path / "pasted.jsonl", tmp_path / "built-in.jsonl"
    build_scenario(document).run(until=until, trace=pasted)
    parse_scenario(scenario_text(case)).run(until=until, trace=built_in)
    assert compare_traces(built_in, pasted, 0.0).identical


def test_an_altered_golden_trace_is_refused_naming_it(
    corpus: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _edit_golden(corpus, "ladder-11-pit", rehash=False)
    code, _, err = invoke(["corpus", "check", str(corpus)], capsys)
    line = one_error(code, err)
    assert "golden/ladder-11-pit.jsonl: altered" in line and "case 'ladder-11-pit'" in line


def test_a_golden_trace_the_run_leaves_fails_its_case(
    corpus: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _edit_golden(corpus, "ladder-11-pit", rehash=True)
    code, out, err = invoke(["corpus", "check", str(corpus)], capsys)
    assert code == 1, out + err
    assert "f32-dart arithmetic pass" in out
    assert "ladder-11-pit ladder FAIL" in out and "origin[0]" in out
    assert "1 passed, 1 failed" in out
    # Within a tolerance the edit passes.
    assert invoke(["corpus", "check", str(corpus), "--tol", "0.01"], capsys)[0] == 0


def test_a_ports_traces_are_checked_without_running(
    corpus: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    port = Path(shutil.copytree(corpus / "golden", tmp_path / "port"))
    code, out, _ = invoke(["corpus", "check", str(corpus), "--trace-dir", str(port)], capsys)
    assert code == 0 and "2 passed, 0 failed" in out
    _edit(port / "f32-dart.jsonl", "cell", "0xA9B40001")
    check = ["corpus", "check", str(corpus), "--trace-dir", str(port)]
    code, out, _ = invoke(check, capsys)
    assert code == 1 and "f32-dart arithmetic FAIL" in out and "cell" in out
    assert "ladder-11-pit ladder pass" in out
    # Ignoring the field, the rest still matches; a missing trace fails its case.
    assert invoke([*check, "--ignore", "cell"], capsys)[0] == 0
    (port / "ladder-11-pit.jsonl").unlink()
    code, out, _ = invoke([*check, "--cases", "ladder-11-pit"], capsys)
    assert code == 1 and "ladder-11-pit ladder FAIL" in out and "cannot open: no such file" in out


def test_a_corpus_reached_through_a_link_is_checked(
    corpus: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    link = tmp_path / "link"
    link.symlink_to(corpus)
    assert invoke(["corpus", "check", str(link), "--cases", "f32-dart"], capsys)[0] == 0


def test_a_corpus_of_another_acphys_is_checked_with_a_warning(
    corpus: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    manifest = _manifest(corpus)
    manifest["acphys"] = "0.0.1"
    (corpus / MANIFEST).write_text(json.dumps(manifest), encoding="utf-8")
    code, _, err = invoke(["corpus", "check", str(corpus), "--cases", "f32-dart"], capsys)
    assert code == 0
    assert err == f"acphys: warning: {corpus}: exported by acphys 0.0.1, checked by {acphys.__version__}\n"


def test_export_refuses_a_folder_that_is_not_a_corpus(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "notes.txt").write_text("mine", encoding="utf-8")
    code, _, err = invoke(["corpus", "export", str(tmp_path), "--cases", "f32-dart"], capsys)
    assert "not empty and not an acphys corpus" in one_error(code, err)
    assert os.listdir(tmp_path) == ["notes.txt"]


def test_export_replaces_an_earlier_corpus(corpus: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (corpus / "keep.txt").write_text("mine", encoding="utf-8")
    assert invoke(["corpus", "export", str(corpus), "--cases", "f32-dart"], capsys)[0] == 0
    assert sorted(os.listdir(corpus / "golden")) == ["f32-dart.jsonl"]
    assert (corpus / "keep.txt").exists()
    # A file in the way that the old manifest does not list is not overwritten.
    (corpus / "golden" / "ladder-11-pit.jsonl").write_text("mine", encoding="utf-8")
    code, _, err = invoke(["corpus", "export", str(corpus), "--cases", ",".join(SMALL)], capsys)
    assert "ladder-11-pit.jsonl: is in the way" in one_error(code, err)
    assert invoke(["corpus", "check", str(corpus)], capsys)[0] == 0  # refused before any change
    # Nor is anything removed through a folder linked out of the corpus.
    (corpus / "golden").rename(corpus.parent / "elsewhere")
    (corpus / "golden").symlink_to(corpus.parent / "elsewhere")
    code, _, err = invoke(["corpus", "export", str(corpus), "--cases", "f32-dart"], capsys)
    assert "golden: not a folder" in one_error(code, err)
    assert (corpus.parent / "elsewhere" / "f32-dart.jsonl").exists()


def _manifest(corpus: Path) -> dict:
    return json.loads((corpus / MANIFEST).read_text(encoding="utf-8"))


def _damage(corpus: Path, how: str) -> str:
    """Damage the corpus ``how``; returns what the error line must say."""
    manifest_path = corpus / MANIFEST
    golden = corpus / "golden" / "f32-dart.jsonl"
    if how == "not JSON":
        manifest_path.write_text('{"format": ', encoding="utf-8")
        return "manifest.json: not JSON"
    if how == "deep JSON":
        manifest_path.write_text("[" * 100_000, encoding="utf-8")
        return "manifest.json: not JSON"
    if how == "5,000 digits":
        manifest_path.write_text('{"format": ' + "9" * 5000 + "}", encoding="utf-8")
        return "manifest.json: not JSON acphys reads"
    if how == "not a manifest":
        manifest_path.write_text('{"cases": []}', encoding="utf-8")
        return "manifest.json: not an acphys corpus manifest"
    if how == "escaping path":
        manifest = _manifest(corpus)
        manifest["cases"][1]["golden"]["path"] = "../../elsewhere.jsonl"
        manifest_path.write_text(json.dumps(manifest), encoding="utf-8")
        return "manifest.json: case 'f32-dart': golden.path must be 'golden/f32-dart.jsonl'"
    if how == "bad name":
        manifest = _manifest(corpus)
        manifest["cases"][1]["name"] = "../f32-dart"
        manifest_path.write_text(json.dumps(manifest), encoding="utf-8")
        return "is not a case name"
    if how == "endless":
        manifest = _manifest(corpus)
        manifest["cases"][1]["until"] = 1e12
        manifest_path.write_text(json.dumps(manifest), encoding="utf-8")
        return "manifest.json: case 'f32-dart': until: running to 1e+12 s"
    if how == "altered built-in":
        with (corpus / "builtins" / "humanoid.toml").open("a", encoding="utf-8") as file:
            file.write("\n")
        return "builtins/humanoid.toml: altered"
    if how == "file out of the corpus":
        manifest = _manifest(corpus)
        manifest["files"][0]["path"] = "builtins/../../human.toml"
        manifest_path.write_text(json.dumps(manifest), encoding="utf-8")
        return "manifest.json: files[0]: path must be FOLDER/NAME.EXT, within the corpus"
    if how == "missing":
        golden.unlink()
        return "golden/f32-dart.jsonl: missing from the corpus"
    if how == "symlink":
        target = corpus.parent / "elsewhere.jsonl"
        golden.rename(target)
        golden.symlink_to(target)
        return "golden/f32-dart.jsonl: a symbolic link"
    if how == "linked folder":
        (corpus / "golden").rename(corpus.parent / "golden")
        (corpus / "golden").symlink_to(corpus.parent / "golden")
        return "golden: a symbolic link"
    if how == "FIFO":
        golden.unlink()
        os.mkfifo(golden)
        return "golden/f32-dart.jsonl: not a regular file (a FIFO)"
    assert how == "manifest is a FIFO"
    manifest_path.unlink()
    os.mkfifo(manifest_path)
    return "manifest.json: not a regular file (a FIFO)"


DAMAGE = [
    "not JSON",
    "deep JSON",
    "5,000 digits",
    "not a manifest",
    "escaping path",
    "bad name",
    "endless",
    "altered built-in",
    "file out of the corpus",
    "missing",
    "symlink",
    "linked folder",
    "FIFO",
    "manifest is a FIFO",
]


@pytest.mark.parametrize("how", DAMAGE)
def test_a_damaged_corpus_is_one_error_line(
    corpus: Path, how: str, capsys: pytest.CaptureFixture[str]
) -> None:
    expected = _damage(corpus, how)
    code, _, err = invoke(["corpus", "check", str(corpus)], capsys)
    assert expected in one_error(code, err)


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["corpus", "check", "{missing}"], "no such folder"),
        (["corpus", "check", "{empty}"], "not an acphys corpus (no manifest.json)"),
        (["corpus", "check", "{corpus}", "--cases", "nope"], "manifest.json: no case 'nope'"),
        (["corpus", "check", "{corpus}", "--tol", "-1"], "--tol must be a non-negative number"),
        (["corpus", "check", "{corpus}", "--ignore", "colour"], "unknown field 'colour'"),
        (["corpus", "check", "{corpus}", "--trace-dir", "{missing}"], "not a folder of traces"),
        (["corpus", "export", "{missing}", "--cases", "nope"], "no corpus case 'nope'"),
        (["corpus", "export", "{file}"], "not a folder"),
    ],
)
def test_bad_arguments_are_one_error_line(
    corpus: Path, tmp_path: Path, argv: list[str], expected: str, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "empty").mkdir()
    (tmp_path / "file").write_text("", encoding="utf-8")
    places = {"corpus": corpus, "missing": tmp_path / "missing", "empty": tmp_path / "empty"}
    places["file"] = tmp_path / "file"
    code, _, err = invoke([arg.format(**places) for arg in argv], capsys)
    assert expected in one_error(code, err)
