"""Output folders named for what is in them (issue 30): ``spsc bladder`` and ``spsc mold`` with
overrides do not write into the preset's folder."""

import pytest

from spsc.cli.bladder import option_labels, output_name
from spsc.cli.main import build_parser, main
from spsc.cli.options import geometry_from_args


def _bladder_name(*argv):
    args = build_parser().parse_args(["bladder", *argv])
    return output_name("bladder", args, geometry_from_args(args),
                       (("flange_holes", args.flange_holes, 4),))


@pytest.mark.parametrize("argv, name", [
    (["--type", "D"], "bladder-D"),
    (["--type", "d", "--w", "11"], "bladder-D"),  # the preset's own value: the preset
    (["--type", "D", "--w", "12"], "bladder-D-w=12"),
    (["--type", "D", "--t0", "1.2", "--n2", "2.5"], "bladder-D-t0=1.2-n2=2.5"),
    (["--type", "D", "--footprint", "GS1"], "bladder-D-GS1"),
    (["--type", "B", "--flange-holes", "2"], "bladder-B-flange_holes=2"),
    (["--w", "11", "--h", "13", "--l", "3", "--t0", "1", "--n1", "2", "--n2", "2.2", "--cy",
      "0.6"], "bladder-w=11-h=13-l=3-t0=1-n1=2-n2=2.2-cy=0.6"),
])
def test_a_folder_is_named_for_its_bladder(argv, name):
    assert _bladder_name(*argv) == name


def test_option_labels_name_only_what_differs():
    assert option_labels((("process", " Compression ", "casting"), ("wall", 5.0, 5.0),
                          ("shrinkage", None, None), ("clearance", 0.25, 0.2))) == \
        ["process=compression", "clearance=0.25"]


def test_bladder_with_an_override_leaves_the_preset_folder_alone(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["bladder", "--type", "A", "--no-check"]) == 0
    before = (tmp_path / "build" / "bladder-A" / "bladder-A.stl").read_bytes()
    assert main(["bladder", "--type", "A", "--w", "12", "--no-check"]) == 0
    assert (tmp_path / "build" / "bladder-A-w=12" / "bladder-A-w=12.stl").is_file()
    assert (tmp_path / "build" / "bladder-A" / "bladder-A.stl").read_bytes() == before
    assert sorted(p.name for p in (tmp_path / "build").iterdir()) == ["bladder-A",
                                                                       "bladder-A-w=12"]


def test_mold_folder_names_its_overrides():
    from spsc.cli import mold

    args = build_parser().parse_args(["mold", "--type", "D", "--w", "12", "--process",
                                      "compression", "--clearance", "0.3"])
    assert mold._bladder(args)[1] == "mold-D-w=12-process=compression-clearance=0.3"
    args = build_parser().parse_args(["mold", "--type", "B"])
    assert mold._bladder(args)[1] == "mold-B"
