"""Progress on stderr (issue 53, item 5): tqdm's bar on a terminal, plain lines in a file or a
pipe (no carriage returns, no cursor moves), a line at the start, after a change every
``every_s`` and at the end; no total (and no time left) where the end is not known."""

from __future__ import annotations

import io

from tqdm import tqdm

from spsc.cli.main import main
from spsc.core.progress import PlainProgress, progress_bar


class _Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


def test_plain_lines_where_stderr_is_not_a_terminal(monkeypatch):
    clock = _Clock()
    monkeypatch.setattr("spsc.core.progress.time.monotonic", clock)
    out = io.StringIO()
    bar = progress_bar(desc="spsc sweep", total=4, unit="design", file=out, every_s=10.0)
    assert isinstance(bar, PlainProgress)
    bar.update(1)  # within the interval: no line
    clock.t += 12.0
    bar.update(1)
    bar.set_postfix(failed=1)
    assert bar.postfix == "failed=1"
    bar.set_postfix_str("best 0.8")
    clock.t += 75.0
    bar.close()
    lines = out.getvalue().splitlines()
    assert lines == ["spsc sweep: 0/4 design, 0.0 s", "spsc sweep: 2/4 design, 12.0 s",
                     "spsc sweep: 2/4 design, 1 min 27 s (best 0.8) (done)"]
    assert "\r" not in out.getvalue() and "\x1b" not in out.getvalue()


def test_no_total_where_the_end_is_not_known():
    out = io.StringIO()
    with progress_bar(desc="spsc design (at most 100 trials)", unit="trial", file=out) as bar:
        bar.update(3)
    assert out.getvalue().splitlines()[-1].startswith("spsc design (at most 100 trials): 3 "
                                                      "trial, ")


def test_a_terminal_gets_the_bar_and_quiet_gets_nothing():
    class Tty(io.StringIO):
        def isatty(self):
            return True

    assert isinstance(progress_bar(desc="x", total=2, file=Tty()), tqdm)
    out = io.StringIO()
    progress_bar(desc="x", total=2, file=out, disable=True).close()
    assert out.getvalue() == ""


def test_a_curve_to_a_redirected_stderr_writes_plain_lines(capsys):
    assert main(["curve", "--model", "wall", "--type", "B", "--l", "0", "--pressure", "20",
                 "--stroke", "1", "--points", "3", "--mesh-size", "1"]) == 0
    err = capsys.readouterr().err
    assert "\r" not in err and "\x1b" not in err
    assert err.splitlines()[-1].startswith("spsc curve: 4/4 step, ") and "(done)" in err
