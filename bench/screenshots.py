"""The documentation's screenshots, regenerated from what they show (issue 53): each page
opened in headless Chromium at a stated window and saved where the guides link it.

* ``docs/img/report-first-screen.png``: the committed report's first screen
  (``reports/validation/index.html``, 1280 x 900), the report guide's;
* ``docs/img/fatigue-C.png``: ``spsc fatigue --type C --png`` (the durability guide's).

    python bench/screenshots.py [--chromium PATH]

Chromium is Debian's ``chromium`` (``apt-get install chromium``); it is not a dependency of the
package, only of this script.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMG = ROOT / "docs" / "img"


def screenshot(chromium: str, page: Path, out: Path, size=(1280, 900)) -> None:
    """``page`` (an HTML file) rendered headless at ``size`` into ``out`` (PNG)."""
    cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           f"--window-size={size[0]},{size[1]}", f"--screenshot={out}",
           page.resolve().as_uri()]
    subprocess.run(cmd, check=True, capture_output=True, timeout=120)
    if not out.is_file() or out.stat().st_size < 10_000:
        raise RuntimeError(f"no screenshot of {page} ({' '.join(cmd)})")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    args = ap.parse_args()
    report = ROOT / "reports" / "validation" / "index.html"
    screenshot(args.chromium, report, IMG / "report-first-screen.png")
    print(f"{IMG / 'report-first-screen.png'} <- {report}")
    fatigue = [sys.executable, "-m", "spsc.cli.main", "fatigue", "--type", "C", "--png",
               str(IMG / "fatigue-C.png"), "--quiet"]
    subprocess.run(fatigue, check=True, cwd=ROOT)
    print(f"{IMG / 'fatigue-C.png'} <- {' '.join(fatigue[2:])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
