"""The figure of ``spsc curve --png``: F, p, A, ΔV and the stiffness over the travel, the
membrane's meridians, the snap-throughs followed, a band where one was asked for; its title
and axes from the setup."""

from __future__ import annotations

from spsc.cad.geometry import FORM, LENGTHS

__all__ = ["plot", "title", "contact_words", "travel_label"]


def plot(curve, result, path, band=None) -> None:
    """F, p, A, ΔV and dF/dy against y; the membrane's deformed meridians (inflated and last
    position) when ``result`` has them; the P5–P95 band and the median of ``band``
    (:func:`spsc.study.band.band`) behind F, p, A and ΔV."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 3, figsize=(12, 6.5), constrained_layout=True)
    y = curve.y_mm
    xlabel = travel_label(curve.setup)
    for a, (val, lab) in zip(ax.flat, ((curve.force_N, "force (N)"),
                                       (curve.pressure_kPa, "gauge pressure (kPa)"),
                                       (curve.contact_area_mm2, "contact area (mm²)"),
                                       (curve.volume_change_mm3, "volume change (mm³)"),
                                       (curve.stiffness(), "stiffness dF/dy (N/mm)"))):
        a.plot(y, val, "o-", ms=2.5, label="nominal")
        col = {"force (N)": "force_N", "gauge pressure (kPa)": "pressure_kPa",
               "contact area (mm²)": "contact_area_mm2",
               "volume change (mm³)": "volume_change_mm3"}.get(lab)
        if band is not None and col is not None:
            q, yb = band[col], band["y_mm"]
            a.fill_between(yb, q["p5"], q["p95"], color="C0", alpha=0.2, lw=0,
                           label="P5–P95 under the tolerance")
            a.plot(yb, q["p50"], "--", color="C0", lw=1, label="median")
            if lab == "force (N)":
                a.legend(fontsize=8, loc="upper left")
        a.set_xlabel(xlabel)
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
    own = curve.series.get("indenter_travel_mm")
    if own is not None:  # on a spring the indenter's own travel is not the far end's
        ax.flat[0].plot(own, curve.force_N, "s--", ms=2.5, color="C1",
                        label="against the indenter's own travel")
        ax.flat[0].legend(fontsize=8, loc="upper left")
    _mark_jumps(curve, ax.flat[0], ax.flat[1])
    a = ax.flat[5]
    if result is not None and getattr(result, "inflated", None) is not None:
        sh = result.inflated
        a.plot(sh.x, sh.y, "k:", label="nominal")
        a.plot(sh.rho, sh.eta, "b-", label="inflated")
        k = max(i for i, s in enumerate(result.shapes) if s is not None)
        last = result.shapes[k]
        if k > 0:
            _, rho, eta = last.meridian()
            a.plot(rho, eta, "r-", label=f"y = {curve.y_mm[k]:.2f} mm")
            a.axhline(last.eta[last.gamma_index], color="0.5", lw=0.8)
        a.set_aspect("equal")
        a.set_xlabel("radius (mm)")
        a.set_ylabel("height (mm)")
        a.legend(fontsize=8)
    else:
        a.axis("off")
    fig.suptitle(title(curve))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _mark_jumps(curve, force_ax, pressure_ax) -> None:
    """Each snap-through the solver followed (``solver.details["jumps"]``): the jump at its
    plate travel from the state before to the state after, with the energy it released."""
    details = curve.solver.details if curve.solver is not None else None
    jumps = (details or {}).get("jumps") or []
    for k, j in enumerate(jumps):
        label = "snap-through (followed)" if k == 0 else None
        for a, key in ((force_ax, "force"), (pressure_ax, "pressure")):
            unit = "N" if key == "force" else "kPa"
            before, after = j[f"{key}_before_{unit}"], j[f"{key}_after_{unit}"]
            a.plot([j["y_mm"]] * 2, [before, after], "r--", lw=1.2, label=label)
            a.plot([j["y_mm"]], [after], "rv", ms=5)
        force_ax.annotate(f"{j['energy_released_mJ']:.2g} mJ", (j["y_mm"], j["force_after_N"]),
                          textcoords="offset points", xytext=(6, -12), fontsize=8, color="r")
    if jumps:
        force_ax.legend(fontsize=8, loc="upper left")


def title(curve) -> str:
    """The figure's title: the model, the chamber (its seven parameters, lengths in mm, or the
    part file), the material, the load case (p_i kPa gauge, V_r mm³, polytropic n) and what
    pressed it when it is not the paper's frictionless rigid plate."""
    g, s = curve.geometry, curve.setup
    part = s.get("part")
    lengths = ", ".join(f"{k}={g[k]:g}" for k in LENGTHS if _is_number(g.get(k)))
    shape = ", ".join(f"{k}={g[k]:g}" for k in FORM if _is_number(g.get(k)))
    dims = "; ".join(x for x in ((f"{lengths} mm" if lengths else ""), shape) if x)
    what = (f"{part['file']} (fix {part['fix']})" if isinstance(part, dict) else
            dims if dims else "no geometry")
    load = [f"{label}={s[key]:g}{unit}" for key, label, unit in
            (("p_i_kPa", "p_i", " kPa"), ("reservoir_mm3", "V_r", " mm³"),
             ("polytropic_n", "n", "")) if _is_number(s.get(key))]
    return f"{curve.model}: {what}; {curve.material}, " + ", ".join(load + contact_words(s))


def contact_words(setup) -> list[str]:
    """What pressed the chamber, in words, where it is not the paper's frictionless rigid
    plate: the body, the friction, the object's spring."""
    from spsc.core.setup import SetupRecord

    r = SetupRecord.of(setup)
    out = [] if r.indenter == "plate" else [f"pressed by {r.indenter}"]
    if r.friction == "stick":
        out.append("sticking")
    elif r.friction != "0":
        out.append(f"μ = {r.friction}")
    if r.object_stiffness_N_per_mm is not None:
        out.append(f"object on a {r.object_stiffness_N_per_mm:g} N/mm spring")
    return out


def travel_label(setup) -> str:
    """The x axis: whose travel y is (the plate's, a curved body's tip, or the far end of
    the object's spring)."""
    from spsc.core.setup import SetupRecord

    r = SetupRecord.of(setup)
    if r.object_stiffness_N_per_mm is not None:
        return "travel of the spring's far end y (mm)"
    if r.indenter == "plate":
        return "plate travel y (mm)"
    return f"{r.indenter.split(':')[0]} tip travel y (mm)"


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)
