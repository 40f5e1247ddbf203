"""``spsc sense --design FILE``: the chamber of a bladder's design file or of ``spsc design``'s
design.json, checked in one line; the same chamber as the geometry options give."""

from __future__ import annotations

import json

import pytest

from spsc.cad.geometry import preset
from spsc.cad.design_file import design_chamber
from spsc.cli.main import build_parser
from spsc.cli.sense import _check_chamber
from spsc.core.errors import ParameterError

B = preset("B")


def _bladder(tmp_path, geometry=None):
    path = tmp_path / "b.design.json"
    path.write_text(json.dumps({"geometry": geometry or B.as_dict(), "genus": 0}))
    return path


def _designed(tmp_path, best=True):
    params = {**preset("C").as_dict(), "type": "C", "material": "elastic50a", "pressure": 25.0,
              "reservoir": 0.0}
    doc = {"schema": "spsc.design", "schema_version": 1,
           "best": {"trial": 3, "params": params} if best else None}
    path = tmp_path / "design.json"
    path.write_text(json.dumps(doc))
    return path


def _args(*argv):
    return build_parser().parse_args(["sense", "log.csv", "--out", "o", *argv])


def test_a_bladder_design_file_is_its_chamber(tmp_path):
    args = _args("--design", str(_bladder(tmp_path)))
    assert _check_chamber(args).as_dict() == B.as_dict()
    assert (args.material, args.pressure) == ("tpu60a", 40.0)


def test_spsc_design_s_best_brings_its_material_and_pressure_unless_given(tmp_path):
    path = _designed(tmp_path)
    args = _args("--design", str(path))
    assert _check_chamber(args).as_dict() == preset("C").as_dict()
    assert (args.material, args.pressure) == ("elastic50a", 25.0)
    args = _args("--design", str(path), "--material", "tpu60a", "--pressure", "30")
    _check_chamber(args)
    assert (args.material, args.pressure) == ("tpu60a", 30.0)


@pytest.mark.parametrize("make, extra, match", [
    (_bladder, ("--type", "B"), "--type = 'B' is invalid: allowed not with --design"),
    (_bladder, ("--w", "12"), "--w = '12' is invalid: allowed not with --design"),
    (lambda t: t / "missing.design.json", (), "design = "),
    (lambda t: _designed(t, best=False), (), "found a best design"),
    (lambda t: _bladder(t, {"w": 11}), (), "geometry"),
])
def test_bad_design_files_are_one_line(tmp_path, make, extra, match):
    with pytest.raises(ParameterError) as err:
        _check_chamber(_args("--design", str(make(tmp_path)), *extra))
    assert match in str(err.value) and "\n" not in str(err.value)


def test_a_design_file_that_is_not_json_is_refused(tmp_path):
    path = tmp_path / "x.design.json"
    path.write_text("{not json")
    with pytest.raises(ParameterError, match="design"):
        design_chamber(path)
