"""Issue 47's layout figures for a commit: the kPa <-> MPa conversions in ``src/`` written out
(KPA_PER_MPA, ``* 1e3`` / ``/ 1e3`` / ``* 1000`` / ``/ 1000`` on a line that names a pressure:
some are mm³ -> cm³ on such a line) and those through the one place
(``spsc.core.constants``' to_MPa/to_kPa/P_AMB_KPA, ``LoadCase.pressure_MPa``), and the literal
tuples of the seven design parameter names (``"w", "h", "l", "t0",
"n1", "n2", "cy"`` written out instead of ``spsc.cad.geometry.PARAMS``).

    python bench/count_layout.py [COMMIT ...]      (default: HEAD)
"""

from __future__ import annotations

import re
import subprocess
import sys

LITERAL = re.compile(r"KPA_PER_MPA|[*/]\s*1e3\b|[*/]\s*1000(\.0)?\b")
NAMED = re.compile(r"to_MPa\(|to_kPa\(|pressure_MPa\b|P_AMB_KPA")
PRESSURE = re.compile(r"kPa|MPa|pressure|_kpa|_mpa|p_i\b", re.I)
NAMES = re.compile(r"""\(\s*["']w["']\s*,\s*["']h["']\s*,\s*["']l["']\s*,\s*["']t0["']\s*,"""
                   r"""\s*["']n1["']\s*,\s*["']n2["']\s*,\s*["']cy["']""")


def count(commit: str) -> dict:
    files = subprocess.run(["git", "ls-tree", "-r", "--name-only", commit, "src/"],
                           capture_output=True, text=True, check=True).stdout.split()
    conv, named, names = {}, {}, {}
    for f in files:
        if not f.endswith(".py") or f.endswith("core/constants.py"):
            continue
        text = subprocess.run(["git", "show", f"{commit}:{f}"], capture_output=True,
                              text=True, check=True).stdout
        lines = [line for line in text.splitlines()
                 if not line.lstrip().startswith(("#", "import", "from"))]
        c = sum(1 for line in lines if LITERAL.search(line) and PRESSURE.search(line))
        k = sum(1 for line in lines if NAMED.search(line))
        n = len(NAMES.findall(text))
        if c:
            conv[f] = c
        if k:
            named[f] = k
        if n:
            names[f] = n
    return {"conversions": sum(conv.values()), "conversion_modules": len(conv),
            "through_named": sum(named.values()), "named_modules": len(named),
            "name_tuples": sum(names.values()), "name_tuple_modules": len(names)}


if __name__ == "__main__":
    for commit in sys.argv[1:] or ["HEAD"]:
        print(commit, count(commit))
