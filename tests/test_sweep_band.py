"""Each design's band in a sweep (issue 49): ``spsc sweep --tolerance FILE`` with the
surrogate adds the P5/P50/P95 of every design's stiffness and sensitivity in both modes; a
spread that vanishes gives the nominal row's metrics back; rows with a band are keyed apart
from rows without, and a re-run resumes; the page draws the band; other models and a lone
--band-samples are refused in one line."""

from __future__ import annotations

import pandas as pd
import pytest
from numpy.testing import assert_allclose

from spsc.cli.main import main
from spsc.sweep.band import BAND_COLUMNS

SPACE = ["--model", "surrogate", "--type", "B", "--l", "0", "--t0", "0.9,1.2", "--w", "10,12",
         "--workers", "1", "--quiet"]
TOL = ('[t0]\ndist = "normal"\nsd = {sd}\n[pressure]\ndist = "normal"\nsd = {sdp}\n'
       '[material]\ndist = "lognormal"\ncv = {cv}\n')


def _sweep(tmp_path, name, *extra):
    out = tmp_path / f"{name}.parquet"
    assert main(["sweep", *SPACE, "--out", str(out), *extra]) == 0
    return pd.read_parquet(out)


def test_each_design_carries_its_band(tmp_path, capsys):
    tol = tmp_path / "tol.toml"
    tol.write_text(TOL.format(sd=0.05, sdp=0.5, cv=0.1))
    df = _sweep(tmp_path, "s", "--tolerance", str(tol), "--band-samples", "16",
                "--html", str(tmp_path / "page"))
    assert set(BAND_COLUMNS) <= set(df.columns) and (df.status == "ok").all()
    for mode in ("high", "low"):
        for m in ("stiffness", "sensitivity"):
            p5, p50, p95 = (df[f"{m}_{mode}_p{q}"] for q in (5, 50, 95))
            assert (p5 < p50).all() and (p50 < p95).all()
            # the median print is the nominal design within the spread's skew (2 %)
            assert_allclose(p50, df[f"{m}_{mode}"], rtol=0.02)
    assert (df.band_samples == 2 * 16 * (3 + 2)).all() and (df.band_refused == 0).all()
    assert (tmp_path / "page" / "figures" / "band.png").stat().st_size > 10_000
    capsys.readouterr()
    again = main(["sweep", *SPACE, "--out", str(tmp_path / "s.parquet"), "--tolerance",
                  str(tol), "--band-samples", "16"])
    assert again == 0 and "4 done earlier and skipped" in capsys.readouterr().out
    plain = _sweep(tmp_path, "s", )  # the same table without a band: its own rows
    assert plain.stiffness_high_p50.isna().all()
    assert not set(plain.key) & set(df.key)


@pytest.mark.slow
def test_a_vanishing_spread_is_the_nominal_design(tmp_path):
    """sd 1e-6 mm, 1e-6 kPa, cv 1e-6: every print is the design itself; its band collapses
    onto the row's own metrics (the band and the row run the same model)."""
    tol = tmp_path / "tol.toml"
    tol.write_text(TOL.format(sd=1e-6, sdp=1e-6, cv=1e-6))
    df = _sweep(tmp_path, "z", "--tolerance", str(tol), "--band-samples", "8")
    for mode in ("high", "low"):
        for m in ("stiffness", "sensitivity"):
            for q in (5, 50, 95):
                assert_allclose(df[f"{m}_{mode}_p{q}"], df[f"{m}_{mode}"], rtol=1e-4)


@pytest.mark.parametrize("extra, says", [
    (["--model", "membrane", "--tolerance", "T"], "tolerance"),
    (["--band-samples", "8"], "band-samples"),
    (["--tolerance", "T", "--band-samples", "2"], "band-samples")])
def test_a_band_the_sweep_cannot_give_is_one_line(tmp_path, capsys, extra, says):
    tol = tmp_path / "tol.toml"
    tol.write_text(TOL.format(sd=0.05, sdp=0.5, cv=0.1))
    argv = ["sweep", *SPACE, "--out", str(tmp_path / "x.parquet"),
            *[str(tol) if a == "T" else a for a in extra]]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x.parquet").exists()
