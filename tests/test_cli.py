"""The spsc command line: bad input ends in one line naming the parameter, and exit code 2."""

import subprocess
import sys

import pytest

from spsc.pipeline.cli import main


@pytest.mark.parametrize("argv,name", [
    (["bladder", "--type", "E"], "type"),
    (["bladder", "--type", "B", "--n1", "0.5"], "n1"),
    (["bladder", "--type", "B", "--cy", "-1"], "cy"),
    (["bladder", "--type", "B", "--w", "0"], "w"),
    (["bladder", "--w", "5"], "geometry"),
    (["bladder", "--type", "B", "--t0", "-1"], "t0"),
    (["bladder", "--type", "B", "--w", "abc"], "w"),
    (["bladder", "--type", "B", "--material", "rubber"], "material"),
    (["bladder", "--type", "B", "--flange-holes", "3"], "flange.holes"),
    (["fingertip", "--angle", "10"], "angle"),
    (["check", "/nonexistent/part.stl"], None),
])
def test_bad_input_is_one_line_exit_2(argv, name, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith(f"spsc {argv[0]}: error: ")
    if name:
        assert f"error: {name} = " in err


def test_console_script_help():
    out = subprocess.run([sys.executable, "-m", "spsc.pipeline.cli", "--help"],
                         capture_output=True, encoding="utf-8", check=True).stdout
    for verb in ("bladder", "fingertip", "check", "membrane", "identify"):
        assert verb in out
