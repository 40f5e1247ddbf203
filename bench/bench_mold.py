"""Issue 15's mold figures: ``make mold TYPE=A|B|C|D`` end to end (wall clock of the command:
mesh and B-rep molds, gate, files, render), the volume identities and each piece's pull test,
and the gate on the three broken molds.

    .venv/bin/python bench/bench_mold.py
"""

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from spsc.report.mold import broken_molds


def main() -> int:
    spsc = str(Path(sys.executable).with_name("spsc"))
    with tempfile.TemporaryDirectory() as tmp:
        for t in "ABCD":
            out = Path(tmp) / t
            t0 = time.perf_counter()
            rc = subprocess.run([spsc, "mold", "--type", t, "--out", str(out)],
                                capture_output=True, text=True).returncode
            wall = time.perf_counter() - t0
            gate = json.loads((out / "gate.json").read_text())
            checks = {c["name"]: c for c in gate["checks"]}
            w, core = checks["wall_volume"], checks["core_volume"]
            pulls = ", ".join(f"{n[5:]} {c['value']:.2g} mm²/{c['details']['collision_mm3']:.2g} mm³"
                              for n, c in checks.items() if n.startswith("pull_"))
            info = json.loads((out / "mold.json").read_text())
            print(f"Type {t}: exit {rc}, {wall:.1f} s, parting {info['parting']['plane']}, "
                  f"gate {'PASSED' if gate['passed'] else 'FAILED ' + str(gate['failed'])}")
            print(f"  wall volume {100 * w['value']:+.2e} %, symmetric difference "
                  f"{100 * w['details']['symmetric_difference']:.2e} %, core vs cavity+bore "
                  f"{100 * core['value']:+.3f} %")
            print(f"  pull (undercut / later collision): {pulls}")
            print(f"  undercut table (mm²): {info['parting']['undercut_mm2']}")
    for b in broken_molds():
        print(f"broken: {b['case']}: failed {b['failed']}")
        for r in b["reasons"]:
            print(f"    {r}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
