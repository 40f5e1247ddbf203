"""The resolution of tension-test data: how much of a fit's residual is the rounding of the
numbers in the file, so the law choice (:func:`.fit.choose`) does not reward a law for fitting
below it.

A number written with d decimals carries a rounding error uniform over ±½·10⁻ᵈ, of RMS
10⁻ᵈ/√12. The step of a column is 10⁻ᵈ with d the most decimals of any of its values as
written in the file, in its own unit (:func:`spsc.materials.data.read_file` counts them,
trailing zeros included); for data made in code, the decimals of the values read back to 12
significant digits. The stress error of point i is then

    σᵢ² = (ΔP² + (dP/dλ)ᵢ² Δλ²) / 12,

the stress step ΔP (MPa) and the stretch step Δλ (-) carried through the data's own slope
(finite differences). The test's resolution is the root mean square of σᵢ (MPa), the RMS
misfit an exact law leaves on such data.
"""

from __future__ import annotations

import numpy as np

__all__ = ["decimal_step", "resolution_MPa"]

#: Significant digits a value is read back to before its decimals are counted.
SIGNIFICANT = 12


def decimal_step(values) -> float:
    """10⁻ᵈ, d the most decimals any of ``values`` is written with (1 for integers; a value
    in exponent notation counts its exponent: 2.5e-05 has 6 decimals)."""
    most = 0
    for v in np.asarray(values, dtype=float).ravel():
        if not np.isfinite(v) or v == 0.0:
            continue
        text = np.format_float_positional(float(f"{v:.{SIGNIFICANT}g}"), unique=True,
                                          trim="-")
        most = max(most, len(text.split(".")[1]) if "." in text else 0)
    return 10.0 ** -most


def _raw_deformation(d) -> tuple[np.ndarray, float]:
    """The deformation column as written and stretch per unit of it."""
    unit = d.columns.get("unit", "stretch")
    if unit == "stretch":
        return d.stretch, 1.0
    per = 0.01 if unit == "%" else 1.0
    return (d.stretch - 1.0) / per, per


def _step(d, key: str, values) -> float:
    """The column's step in its own unit: from the decimals as written, else the values."""
    written = d.columns.get(key)
    return 10.0 ** -written if written is not None else decimal_step(values)


def resolution_MPa(tests) -> dict:
    """Test -> the RMS stress error (MPa) the rounding of its data makes (module docstring).
    Tests from data without their columns' units (made in code) are taken as stretch and MPa."""
    from ..data import STRESS_UNITS

    out: dict = {}
    for t in dict.fromkeys(d.test for d in tests):
        var = []
        for d in (d for d in tests if d.test == t):
            per_stress = STRESS_UNITS.get(d.columns.get("stress_unit", "MPa"), 1.0)
            dP = _step(d, "stress_decimals", d.stress_MPa / per_stress) * per_stress
            raw, per = _raw_deformation(d)
            dlam = _step(d, "deformation_decimals", raw) * per
            slope = (np.gradient(d.stress_MPa, d.stretch) if d.points >= 2
                     else np.zeros(d.points))
            var.append((dP**2 + (slope * dlam) ** 2) / 12.0)
        out[t] = float(np.sqrt(np.mean(np.concatenate(var))))
    return out
