"""Fuzz test of the error contract over every verb: each invalid invocation of
``spsc_support.fuzz_cases`` (a bad number, a cross-parameter limit, a bad choice, an output that
cannot be written, a bad input file, an argparse mistake) ends in exit 2 and exactly one line on
stderr that names the option at fault — no traceback, no usage dump, and no work started: every
function that builds, solves or checks raises if it is called (and a case still running after
20 s fails too).

Every case carries its class of mistake (``Case.kind``, one of ``KINDS``), and no refused
invocation may leave a file behind (under the fixtures' folder or the current folder). The whole
table (about 2,600 cases) takes about 25 s of CPU in-process (each case builds only its verb's
parser). ``bench/bench_badinput.py`` runs the same table as subprocesses and counts the
outcomes.
"""

from __future__ import annotations

import re
import signal
from pathlib import Path

import pytest

from spsc_support.fuzz_cases import KINDS, Case, classes, invalid_cases
from spsc.cli.main import COMMANDS, main

#: Seconds a case may take in-process: validation is milliseconds; importing the CAD kernel
#: or the FEM the first time a verb runs is about 3 s.
SECONDS = 20


def _name_pattern(name: str) -> str:
    return "".join("[-_ .]" if ch in "-_ ." else re.escape(ch) for ch in name)


@pytest.fixture(scope="module")
def tmp_cases(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz")


class WorkStarted(Exception):
    """Raised by every entry point that does real work: an invalid input must be refused
    before any of them is called."""


#: module -> the functions that do the work (builds, solves, checks, studies); where a command
#: module binds one at import, it is patched there too.
WORK = {
    "spsc.cad.bladder": ["build_bladder"],
    "spsc.cad.fingertip": ["build_fingertip"],
    "spsc.cad.check": ["check_mesh"],
    "spsc.cli.check": ["check_mesh"],
    "spsc.membrane.solver": ["solve"],
    "spsc.membrane.simplified": ["simplified_curve"],
    "spsc.membrane.identify": ["identify"],
    "spsc.fem.solid.chamber": ["run_chamber"],
    "spsc.fem.part.run": ["part_model", "run_part"],
    "spsc.studies.fingertip": ["run_study"],
    "spsc.studies.haptic": ["run_study"],
    "spsc.fem.wall": ["wall_curve"],
    "spsc.fem.wall.calibrate": ["calibrate"],
    "spsc.fem.wall.durability": ["squeeze_cycle", "paper_fatigue_law"],
    "spsc.fem.wall.puncture": ["puncture"],
    "spsc.studies.durability": ["run_study"],
    "spsc.study.runner": ["run_all"],
    "spsc.materials.fit.fitting": ["fit_law", "fit_laws"],
    "spsc.sweep.run": ["run_sweep"],
    "spsc.design.loop": ["run_design"],
    "spsc.study.executor": ["dask_client"],
}


@pytest.fixture
def no_work(monkeypatch):
    import importlib

    def refuse(*args, **kwargs):
        raise WorkStarted("work started before the input was refused")

    modules = {m: importlib.import_module(m) for m in WORK}  # all bound before patching
    for module, names in WORK.items():
        for name in names:
            monkeypatch.setattr(modules[module], name, refuse)


class _Timeout(Exception):
    pass


def _run(case: Case, capsys) -> tuple[int, str, str]:
    def alarm(*_):
        raise _Timeout(f"still running after {SECONDS} s: work started before validation")

    old = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(SECONDS)
    try:
        rc = main(list(case.argv))
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    out, err = capsys.readouterr()
    return rc, out, err


def _check(case: Case, rc: int, out: str, err: str) -> None:
    lines = err.strip().splitlines()
    assert rc == 2, (case.why, rc, err[-500:])
    assert len(lines) == 1, (case.why, err)
    assert "Traceback" not in err and "usage:" not in err, (case.why, err)
    verb = f"spsc {case.verb}" if case.verb in COMMANDS else "spsc"
    # a verb with actions (spsc surrogate train) names the action too
    assert re.match(rf"{re.escape(verb)}( [a-z-]+)?: error: ", lines[0]), (case.why, lines[0])
    if case.names:
        message = lines[0].split(": error: ", 1)[1]
        assert re.search(rf"(?<![A-Za-z_]){_name_pattern(case.names)}(?![A-Za-z_])", message), (
            case.why, case.names, message)


def test_the_table_covers_every_verb(tmp_cases):
    cases = invalid_cases(tmp_cases)
    assert {c.verb for c in cases} >= set(COMMANDS)  # a new verb needs its cases
    assert len(cases) >= 300


def test_the_table_covers_every_class_of_mistake(tmp_cases):
    """Every class of :data:`KINDS` has cases (a new class needs its cases), among them the
    ones of issue 30: tension data, lists of numbers, a part's surface, a design file's schema,
    a port that is not a Dask scheduler, a duplicated item."""
    counts = classes(invalid_cases(tmp_cases))
    assert set(counts) == set(KINDS), set(KINDS) ^ set(counts)


def _files(*roots) -> set:
    return {p for r in roots for p in Path(r).rglob("*") if not p.is_dir()}


#: the table runs in this many shards, each a test of a few seconds (make test keeps a module
#: on one worker: --dist loadscope)
SHARDS = 4


@pytest.mark.parametrize("shard", range(SHARDS))
def test_every_invalid_invocation_is_one_line_exit_2(shard, tmp_cases, capsys, no_work,
                                                     monkeypatch, tmp_path):
    """... and leaves no file behind, under the fixtures' folder or the current folder
    (every ``SHARDS``-th case from ``shard``)."""
    monkeypatch.chdir(tmp_path)
    failures = []
    cases = invalid_cases(tmp_cases)[shard::SHARDS]
    before = _files(tmp_cases, tmp_path)
    for case in cases:
        try:
            rc, out, err = _run(case, capsys)
            _check(case, rc, out, err)
            left = _files(tmp_cases, tmp_path) - before
            assert not left, (case.why, "left behind:", sorted(map(str, left)))
        except (AssertionError, WorkStarted, _Timeout) as exc:
            failures.append(f"spsc {' '.join(map(repr, case.argv))}: {exc}")
            before = _files(tmp_cases, tmp_path)
    assert not failures, f"{len(failures)} cases broke the contract:\n" + "\n".join(failures)


def test_a_part_fem_refused_after_meshing_leaves_no_file(tmp_path, monkeypatch, capsys):
    """A 0.02 mm cavity in a 20 mm box, meshed at 4 mm: fTetWild fills the cavity (it used to
    end in 'v_closed = -0.0 is invalid' with the mesh cached under ./build): one line naming
    the mesh size, and no file anywhere (about 8 s: the meshing is real)."""
    import manifold3d as mf

    from spsc.cad.export import TriMesh, write_stl

    box = mf.Manifold.cube((20.0, 20.0, 20.0)) - mf.Manifold.cube((0.02,) * 3, True).translate(
        (10.0, 10.0, 10.0))
    m = box.to_mesh64()
    (tmp_path / "part").mkdir()
    stl = tmp_path / "part" / "tiny-cavity.stl"
    write_stl(TriMesh(m.vert_properties[:, :3], m.tri_verts.astype("int64")), stl)
    (tmp_path / "out").mkdir()
    monkeypatch.chdir(tmp_path)
    before = _files(tmp_path)
    rc = main(["fem", "--part", str(stl), "--fix", "z<=0", "--quiet", "--mesh-size", "4",
               "--json", str(tmp_path / "out" / "curve.json")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("spsc fem: error: mesh size = 4.0")
    assert _files(tmp_path) == before


def test_the_part_mesh_cache_goes_beside_the_output_named():
    from argparse import Namespace

    from spsc.cli.options import output_cache_dir as cache_dir

    none = dict(cache=None, json=None, csv=None, png=None, vtu=None)
    assert cache_dir(Namespace(**none)) is None  # build/cache/fem under the current folder
    assert cache_dir(Namespace(**none | {"json": "/a/b/x.json", "png": "/c/p.png"})) == Path(
        "/a/b/spsc-cache")
    assert cache_dir(Namespace(**none | {"vtu": "/a/vtu"})) == Path("/a/spsc-cache")
    assert cache_dir(Namespace(**none | {"json": "/a/x.json", "cache": "/k"})) == Path("/k")
    assert cache_dir(Namespace(json="/a/x.json")) == Path("/a/spsc-cache")  # no --cache


def test_spsc_curve_hands_its_model_the_cache_beside_the_output(tmp_path, monkeypatch):
    """The chamber FEM (any model through spsc curve) keeps its meshes beside --json, not
    under the current folder's build/ (issue 30)."""
    from spsc.models import MODELS

    seen = []
    kind = type(MODELS["simplified"])
    real = kind.curve

    def spy(self, *a, cache_dir=None, **k):
        seen.append(cache_dir)
        return real(self, *a, cache_dir=cache_dir, **k)

    monkeypatch.setattr(kind, "curve", spy)
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "elsewhere" / "c.json"
    out.parent.mkdir()
    assert main(["curve", "--type", "B", "--model", "simplified", "--stroke", "1", "--points",
                 "3", "--json", str(out), "--quiet"]) == 0
    assert seen == [out.parent / "spsc-cache"]
