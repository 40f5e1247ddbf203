"""core.jsonio.write_json: atomic for files, and never renames over a device or a pipe (run as
root, ``--json /dev/null`` replaced the null device with a regular file)."""

import json
import os
import stat
import threading

from spsc.core.jsonio import write_json


def test_write_json_into_a_pipe_keeps_the_pipe(tmp_path):
    """A named pipe stands in for /dev/null (the test must not touch /dev): it stays a pipe,
    and the reader gets the JSON."""
    fifo = tmp_path / "out.json"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text(encoding="utf-8")),
                              daemon=True)
    reader.start()
    write_json(fifo, {"a": 1.5})
    reader.join(timeout=10)
    assert stat.S_ISFIFO(fifo.stat().st_mode)
    assert json.loads(got[0]) == {"a": 1.5}
    assert not (tmp_path / "out.json.tmp").exists()


def test_write_json_to_a_file_is_atomic_and_complete(tmp_path):
    path = tmp_path / "x.json"
    path.write_text("old", encoding="utf-8")
    write_json(path, {"b": [1, None]})
    assert json.loads(path.read_text(encoding="utf-8")) == {"b": [1, None]}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.json"]
