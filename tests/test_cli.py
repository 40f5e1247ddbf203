"""The spsc command line: bad input ends in one line naming the parameter, and exit code 2."""

import subprocess
import sys

import pytest

from spsc.pipeline.cli import main


@pytest.mark.parametrize("argv,name", [
    (["bladder", "--type", "E"], "type"),
    (["bladder", "--n1", "0.5"], "n1"),
    (["bladder", "--cy", "-1"], "cy"),
    (["bladder", "--w", "0"], "w"),
    (["bladder", "--t0", "-1"], "t0"),
    (["bladder", "--w", "abc"], "w"),
    (["bladder", "--material", "rubber"], "material"),
    (["bladder", "--flange-holes", "3"], "flange.holes"),
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
                         capture_output=True, text=True, check=True).stdout
    for verb in ("bladder", "fingertip", "check", "membrane", "identify"):
        assert verb in out
