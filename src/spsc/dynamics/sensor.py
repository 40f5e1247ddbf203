"""A pressure sensor on the chamber: sampling rate, white noise and resolution (quantisation),
and the ELVH preset of the paper's sensor.

The paper reads the chamber with an Amphenol All Sensors ELVH-015G-HAND-C-NAA5 (sec. 4:
full scale 100 kPa gauge, ±0.25 % accuracy). Its datasheet gives a 15 psi (103.4 kPa) gauge
range on a 14-bit output spanning 10–90 % of the counts (13,107 counts over the range: 0.0079
kPa a count). The ±0.25 % FS is a total error band, not a noise spectrum: the preset takes it
as ±3σ of white noise (σ = 0.086 kPa), an assumption stated wherever the preset is used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require, require_integer

__all__ = ["Sensor", "PRESETS"]

_ELVH_FS_KPA = 15 * 6.894757  # 15 psi
PRESETS = {
    "elvh": dict(noise_kPa=0.0025 * _ELVH_FS_KPA / 3.0, resolution_kPa=_ELVH_FS_KPA / 13107,
                 full_scale_kPa=_ELVH_FS_KPA),
}


@dataclass(frozen=True)
class Sensor:
    """``rate_Hz`` samples per second, ``noise_kPa`` σ of white noise, ``resolution_kPa`` the
    quantisation step (0: none), ``full_scale_kPa`` the reading's ceiling (gauge, clipped at
    0 and here; 0: no ceiling), ``seed`` of the noise."""

    rate_Hz: float = 1000.0
    noise_kPa: float = 0.0
    resolution_kPa: float = 0.0
    full_scale_kPa: float = 0.0
    seed: int = 0

    def __post_init__(self):
        require("sensor rate_Hz", self.rate_Hz, gt=0, le=1e6, unit="Hz")
        require("sensor noise_kPa", self.noise_kPa, ge=0, unit="kPa")
        require("sensor resolution_kPa", self.resolution_kPa, ge=0, unit="kPa")
        require("sensor full_scale_kPa", self.full_scale_kPa, ge=0, unit="kPa")
        object.__setattr__(self, "seed", require_integer("sensor seed", self.seed, ge=0,
                                                         le=2**63 - 1))

    @classmethod
    def preset(cls, name: str, **overrides) -> "Sensor":
        if name not in PRESETS:
            raise ParameterError("sensor preset", name, "one of " + ", ".join(PRESETS))
        return cls(**{**PRESETS[name], **overrides})

    def times(self, t_end: float) -> np.ndarray:
        """The sampling instants in [0, t_end] (s)."""
        return np.arange(0.0, t_end + 0.5 / self.rate_Hz, 1.0 / self.rate_Hz)

    def read(self, pressure_kPa: np.ndarray) -> np.ndarray:
        """The readings of the true gauge pressures (kPa) at the sampling instants."""
        rng = np.random.default_rng(self.seed)
        p = np.asarray(pressure_kPa, float) + self.noise_kPa * rng.standard_normal(
            np.shape(pressure_kPa))
        if self.resolution_kPa > 0:
            p = np.round(p / self.resolution_kPa) * self.resolution_kPa
        if self.full_scale_kPa > 0:
            p = np.clip(p, 0.0, self.full_scale_kPa)
        return p
