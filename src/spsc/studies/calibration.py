"""What a calibration shows beside the calibrated wall model: the paper's identification
(eqs. 39–40) on the same bench test with its lumped-model predictions (eqs. 6–7), mean slopes
over a stroke, and the figure of the bench test against the calibrated model. Used by
``spsc calibrate`` and by the report's bench section."""

from __future__ import annotations

import numpy as np

__all__ = ["identification", "mean_slope", "plot_calibration"]


def identification(bench, geom, setups, *, pressure_kPa: float, reservoir_mm3: float,
                   polytropic_n: float) -> list:
    """The paper's identification (eqs. 39–40) on the same closed-chamber bench test, and its
    lumped-model predictions (eqs. 6–7) at the same setups; [] for an open chamber's test. V_b,i
    is the nominal cavity; without an elastic_force_N column F_el is taken as 0 (the paper
    measures it separately), so the identified area then carries the wall's force."""
    if pressure_kPa == 0 or bench.pressure_kPa is None or not setups:
        return []
    from spsc.membrane.identify import identify, predict

    vb = geom.cavity_volume()
    ident = identify(bench, pressure_kPa=pressure_kPa, bladder_volume_mm3=vb,
                     reservoir_mm3=reservoir_mm3, polytropic_n=polytropic_n,
                     geometry=geom.as_dict())
    return [predict(ident, pressure_kPa=p, reservoir_mm3=r, bladder_volume_mm3=vb,
                    polytropic_n=polytropic_n, elastic_force_N=bench.elastic_force_N)
            for p, r in setups]


def mean_slope(curve, values, y_end: float) -> float:
    """(v(y_end) − v(0)) / y_end over the converged points (N/mm or kPa/mm)."""
    ok = curve.converged & np.isfinite(values)
    if not ok.any() or curve.y_mm[ok][-1] < y_end - 1e-9:
        return float("nan")
    v = np.interp([0.0, y_end], curve.y_mm[ok], values[ok])
    return float((v[1] - v[0]) / y_end)


def plot_calibration(path, bench, cal, preds, p_i) -> None:
    """Bench vs the calibrated wall model; the predicted forces and pressures."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2), constrained_layout=True)
    c = cal.curve
    ax[0].plot(bench.y_mm, bench.force_N, "ko", ms=3, label="bench")
    ax[0].plot(c.y_mm, c.force_N, "r-", label=f"wall, stiffness x {cal.scale:.3g}")
    ax[0].set_ylabel("force (N)")
    ax[0].set_title("the bench test and the calibrated wall model", fontsize=10)
    if bench.pressure_kPa is not None and p_i > 0:
        ax[2].plot(bench.y_mm, bench.pressure_kPa, "ko", ms=3, label="bench")
        ax[2].plot(c.y_mm, c.pressure_kPa, "r-", label="wall, calibrated")
    for pc in preds:
        label = f"{pc.setup['p_i_kPa']:g} kPa, V_r {pc.setup['reservoir_mm3'] / 1000:g} cm³"
        ax[1].plot(pc.y_mm, pc.force_N, "-", label=label)
        ax[2].plot(pc.y_mm, pc.pressure_kPa, "--", label=label)
    ax[1].set_ylabel("predicted force (N)")
    ax[2].set_ylabel("gauge pressure (kPa)")
    ax[1].set_title("predicted with the calibrated material", fontsize=10)
    for a in ax:
        a.set_xlabel("plate travel y (mm)")
        a.grid(alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
