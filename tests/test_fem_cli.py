"""``spsc fem``: same options and JSON as ``spsc membrane``; exit codes."""

import json

from spsc.core.curve import Curve
from spsc.cli.main import main
from spsc.fem.solid.chamber import ChamberRun


def test_spsc_fem_writes_the_curve_json(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the mesh cache goes beside --json, never under build/ here
    out = tmp_path / "fem.json"
    code = main(["fem", "--type", "B", "--pressure", "40", "--reservoir", "40000",
                 "--stroke", "1", "--points", "3", "--mesh-size", "3", "--layers", "1",
                 "--json", str(out), "--csv", str(tmp_path / "fem.csv"),
                 "--vtu", str(tmp_path / "vtu"), "--quiet"])
    assert code == 0
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["model"] == "fem" and data["setup"]["reservoir_mm3"] == 40000.0
    info = data["solver"]
    assert info["converged"] and info["details"]["dofs"] > 0 and info["details"]["tetrahedra"] > 0
    assert info["iterations"] > 0 and info["seconds"] > 0 and info["details"]["mesh_size_mm"] == 3
    assert data["extra"]["vtu"] == sorted(p.name for p in (tmp_path / "vtu").glob("*.vtu"))
    curve = Curve.from_json(out)
    assert len(curve) == 3 and curve.all_converged and curve.force_N[-1] > 0
    # the start, each inflation increment, each press point
    assert len(list((tmp_path / "vtu").glob("*.vtu"))) == 1 + ChamberRun.inflate_increments + 2
    assert "cavity volume" in capsys.readouterr().out
    assert list((tmp_path / "spsc-cache").rglob("*.npz"))
    assert not (tmp_path / "build").exists()


def test_spsc_fem_bad_input_is_one_line_and_exit_2(capsys):
    assert main(["fem", "--type", "B", "--mesh-size", "0", "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("spsc fem: error: mesh size")


def test_bench_script_runs_small(tmp_path, capsys):
    """bench/bench_fem.py is executed by the suite on a tiny case (both modes)."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "bench" / "bench_fem.py"
    spec = importlib.util.spec_from_file_location("bench_fem", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    out = tmp_path / "rows.json"
    bench.main(["--sizes", "3.0:1", "--stroke", "0.5", "--points", "2", "--cache",
                str(tmp_path), "--json", str(out)])
    rows = json.loads(out.read_text(encoding="utf-8"))
    assert rows[0]["ok"] and rows[0]["force_N"] > 0
    bench.main(["--solvers", "3.0:1", "--solver-list", "pardiso", "superlu"])
    lines = [json.loads(s) for s in capsys.readouterr().out.splitlines() if s.startswith("{")]
    solver_rows = [r for r in lines if "solver" in r]
    assert [r["solver"] for r in solver_rows] == ["pardiso", "superlu"]
    assert solver_rows[0]["negative_pivots"] == solver_rows[0]["pressure_unknowns"]
    assert all(r["residual"] < 1e-10 for r in solver_rows)
