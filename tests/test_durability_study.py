"""The report's durability study (issue 51): spsc fatigue --study writes what the section
shows (every material's calibration, Types A-D, the other strokes and pressures, two
figures), and the section renders its numbers (and says how to make it without)."""

from __future__ import annotations

import json

import pytest

from spsc.cli.main import main
from spsc.materials.catalogue import FATIGUE_TESTS
from spsc.report.durability import durability_section
from spsc.report.render import environment

pytestmark = pytest.mark.slow


def test_the_study_writes_what_the_section_shows(tmp_path, capsys, monkeypatch):
    import spsc.studies.durability as study_module
    from spsc.fem.wall.puncture import MESHES

    monkeypatch.setattr(study_module, "PUNCTURE_MESHES", MESHES[:1])  # the coarse one: 40 s
    study = tmp_path / "durability"
    assert main(["fatigue", "--study", "--out", str(study), "--quiet"]) == 0
    s = json.loads((study / "summary.json").read_text())
    assert set(s["calibration"]) == set(FATIGUE_TESTS) and list(s["types"]) == list("ABCD")
    b = s["types"]["B"]
    # Type B in TPU 60A is the calibration: its life is Table 2's, whatever the exponent
    assert b["life_cycles"] == pytest.approx(4100.0, rel=1e-9)
    assert b["life_other_exponent"] == pytest.approx(4100.0, rel=1e-9)
    assert s["strokes"]["4"]["life_cycles"] > b["life_cycles"] > s["strokes"]["8"]["life_cycles"]
    sec = durability_section(study, tmp_path / "report")
    assert (tmp_path / "report" / sec["lives"]).is_file()
    assert (tmp_path / "report" / sec["fields"]).is_file()
    render = environment().from_string('{% import "macros.html.j2" as m with context %}'
                                       '{% include "durability_section.html.j2" %}').render
    html = " ".join(render(durability=sec).split())
    assert 'id="durability"' in html and "by construction" in html
    assert f"{s['calibration']['elastic50a']['amplitude_MPa']:.4f}" in html
    assert "make durability-study" in render(durability=None)
    # the puncture test: every material walked, the two with a cited criterion judged
    p = s["puncture"]["materials"]
    assert set(p) == set(FATIGUE_TESTS)
    assert p["elastic50a"]["runs"][0]["failure"]["reached"]
    assert not p["tpu60a"]["runs"][0]["failure"]["reached"]
    assert p["as40"]["criterion"] is None and "no datasheet" in p["as40"]["source"]
    assert (tmp_path / "report" / sec["puncture_figure"]).is_file()
    assert "The puncture test" in html and "tearing energy" in html
