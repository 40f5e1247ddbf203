"""The report's section on the user's own bench test: the material calibrated on it through the
wall model (:mod:`spsc.fem.wall.calibrate`) beside the paper's identification (eqs. 39–40) on the
same test, both predicting the study's setup pressures in both modes.

``spsc report --bench FILE --bench-type D --bench-pressure 40`` adds it; without bench data the
report has no such section. Units: mm, N, kPa gauge, N/mm, kPa/mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["BenchSpec", "bench_section"]


@dataclass(frozen=True)
class BenchSpec:
    """A bench test: its CSV, the chamber (a Type preset with ``geometry`` overrides of the
    seven parameters, mm), the starting material (catalogue name or material file), the setup
    pressure (kPa gauge; 0 the open chamber) and reservoir (mm³) of the test."""

    path: str
    type: str
    pressure_kPa: float
    reservoir_mm3: float = 0.0
    material: str = "tpu60a"
    geometry: tuple = ()  # (name, value) pairs

    def check(self):
        """Every input checked before the study runs (one-line ParameterError): the bench
        file, the chamber, the material, the pressure and the stroke against the chamber."""
        from spsc.cad.geometry import preset
        from spsc.core.errors import require
        from spsc.core.loadcase import PRESSURE_MAX_KPA, check_load
        from spsc.core.bench import REQUIRED, read_bench
        from spsc.materials import material

        geom = preset(self.type, **dict(self.geometry))
        mat = material(self.material)
        require("bench_pressure", self.pressure_kPa, ge=0, le=PRESSURE_MAX_KPA, unit="kPa gauge")
        require("bench_reservoir", self.reservoir_mm3, ge=0, unit="mm³")
        bench = read_bench(self.path, required=REQUIRED[:2])
        check_load(geom, pressure_kPa=self.pressure_kPa, reservoir_mm3=self.reservoir_mm3,
                   stroke_mm=float(bench.y_mm[-1]), points=2, polytropic_n=1.0)
        return geom, mat, bench


def bench_section(spec: BenchSpec, study, fig_dir: Path) -> dict:
    """Calibrate, predict the study's pressures × modes with both methods over the bench's
    stroke, draw the figure; the section's data (rows of mean slopes, residuals, the factor)."""
    from spsc.core.setup import Setup
    from spsc.fem.wall.calibrate import calibrate
    from spsc.models import MODELS

    from spsc.studies.calibration import identification, mean_slope, plot_calibration

    geom, mat, bench = spec.check()
    wall = MODELS["wall"]

    def solve(m, stroke_mm, points, p=spec.pressure_kPa, v=spec.reservoir_mm3):
        setup = Setup.of(geom, m, pressure_kPa=p, reservoir_mm3=v, stroke_mm=stroke_mm,
                         points=points)
        return wall.curve(setup, wall.Options()).curve

    cal = calibrate(bench, geom, mat, pressure_kPa=spec.pressure_kPa,
                    reservoir_mm3=spec.reservoir_mm3, solve=solve)
    y_end = float(bench.y_mm[-1])
    setups = [(p, v) for _, v in study.modes for p in study.pressures_kPa]
    preds = [solve(cal.material, y_end, 13, p, v) for p, v in setups]
    idents = identification(bench, geom, setups, pressure_kPa=spec.pressure_kPa,
                            reservoir_mm3=spec.reservoir_mm3, polytropic_n=1.0)
    rows = []
    for k, (p, v) in enumerate(setups):
        w, i = preds[k], (idents[k] if idents else None)
        rows.append({"pressure": p, "reservoir": v,
                     "k_wall": mean_slope(w, w.force_N, y_end),
                     "s_wall": mean_slope(w, w.pressure_kPa, y_end),
                     "k_ident": mean_slope(i, i.force_N, y_end) if i else None,
                     "s_ident": mean_slope(i, i.pressure_kPa, y_end) if i else None})
    figure = "bench-calibration.png"
    plot_calibration(Path(fig_dir) / figure, bench, cal, preds, spec.pressure_kPa)
    return {"file": Path(spec.path).name, "type": spec.type, "pressure": spec.pressure_kPa,
            "reservoir": spec.reservoir_mm3, "material": mat.name, "scale": cal.scale,
            "mu0": cal.material.shear_modulus, "mu0_start": mat.shear_modulus,
            "force_rms": cal.force_rms_N, "pressure_rms": cal.pressure_rms_kPa,
            "relative_rms": cal.relative_rms, "points": int(bench.y_mm.size),
            "y_end": y_end, "rows": rows, "identified": bool(idents), "figure": figure}
