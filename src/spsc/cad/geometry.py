"""SPSC geometry: the seven parameters, the generalised super-ellipse and the analytic cavity.

All lengths in mm, volumes in mm³. The cavity is bounded by the nominal profile (``w`` and ``h``
are the cavity's semi-width at the base and its height); the wall is that profile thickened by
``t0`` along its outward normal. Part coordinates (docs/design.md): base plane z = 0, dome along +z,
extrusion of length ``l`` along y, width along x, cavity centred on the origin.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from spsc.core.errors import ParameterError, require

__all__ = [
    "SPSCGeometry",
    "TYPES",
    "TABLE1_VOLUME_CM3",
    "preset",
    "PARAMS",
    "LENGTHS",
    "FORM",
]

#: The seven parameters of a chamber (mm: w, h, l, t0; dimensionless: n1, n2, c_y), under
#: the names the command line and the tables use.
PARAMS = ("w", "h", "l", "t0", "n1", "n2", "cy")
#: Those that are lengths (mm) and those that are form factors (dimensionless, Table 1).
LENGTHS, FORM = PARAMS[:4], PARAMS[4:]

#: Form factors (n1, n2, c_y) of the four notable types, Table 1.
TYPES: dict[str, tuple[float, float, float]] = {
    "A": (3.0, 4.0, 0.0),
    "B": (2.0, 2.2, 0.0),
    "C": (2.0, 1.0, 0.0),
    "D": (2.0, 2.2, 0.6),
}
#: Nominal cavity volumes V_b,i of Table 1 (cm³), for w = 11, h = 13, l = 3, t0 = 1 mm.
TABLE1_VOLUME_CM3 = {"A": 4.96, "B": 4.09, "C": 3.04, "D": 6.50}
#: Footprints (w, h, l, t0) in mm: Table 1 (sec. 3.1) and the GS1 set (sec. 2.3.3).
SIZES = {"table1": (11.0, 13.0, 3.0, 1.0), "GS1": (10.0, 10.0, 10.0, 1.0)}

#: The design space tests and solvers cover (docs/design.md); outside it a warning, not an error.
DESIGN_SPACE = {
    "n1": (2.0, 8.0),
    "n2": (1.0, 8.0),
    "cy": (0.0, 0.9),
    "h/w": (0.5, 2.0),
    "l/w": (0.0, 3.0),
    "t0/w": (0.02, 0.2),
}


#: Points of the profile polylines of the export mesh (:mod:`spsc.cad.meshbuild`, the mesh the
#: printability gate checks): spacing ~0.2 mm on Table 1 chambers, sag < 0.002 mm.
MESH_PROFILE_POINTS = 161

#: Lengths below this (mm) are zero: OCCT's Precision::Confusion.
LENGTH_CONFUSION_MM = 1e-7

#: Hard limits, refused with a ParameterError (the design space above only warns). Lengths in
#: mm: 0.1 mm is under every process's resolution, 500 mm beyond any printer's build volume.
#: Ratios: beyond them the profile, its offset and the solvers' meridians degenerate (h/w
#: 1e-8 broke the membrane's spline, n1 = 1e9 the FEM's section). w̄/w, the widest half-width
#: over the base half-width (eq. 14), bounds c_y → 1, where w̄ → ∞ (eq. 12: Δu → 0).
LIMITS = {
    "length_mm": (0.1, 500.0),
    "n": (1.0, 20.0),
    "h/w": (0.1, 10.0),
    "l/w": (0.0, 20.0),
    "t0/w": (1e-3, 1.0),
    "w_bar/w": 5.0,
}


@dataclass(frozen=True)
class SPSCGeometry:
    """The seven parameters of an SPSC (sec. 2.2).

    Parameters
    ----------
    w, h : float
        Cavity semi-width at the clamped edge and cavity height (mm), > 0.
    l : float
        Length of the extruded middle part (mm), >= 0; ``l = 0`` is a pure dome (so is any
        l < 1e-7 mm, which no solid modeller can tell from zero).
    t0 : float
        Wall thickness (mm), > 0. A wall under a process minimum is valid geometry; it fails the
        printability gate, not this constructor.
    n1, n2 : float
        Super-ellipse exponents (eqs. 10–11), >= 1.
    cy : float
        Vertical shift of the super-ellipse (eq. 11), >= 0.
    """

    w: float
    h: float
    l: float
    t0: float
    n1: float
    n2: float
    cy: float

    def __post_init__(self):
        lo, hi = LIMITS["length_mm"]
        n_lo, n_hi = LIMITS["n"]
        for name, kw in (("w", dict(ge=lo, le=hi)), ("h", dict(ge=lo, le=hi)),
                         ("l", dict(ge=0, le=hi)), ("t0", dict(gt=0)),
                         ("n1", dict(ge=n_lo, le=n_hi)), ("n2", dict(ge=n_lo, le=n_hi)),
                         ("cy", dict(ge=0, lt=1))):
            unit = "mm" if name in "w h l t0" else ""
            object.__setattr__(self, name, require(name, getattr(self, name), unit=unit, **kw))
        if self.l < LENGTH_CONFUSION_MM:  # no solid modeller can tell such a length from zero
            object.__setattr__(self, "l", 0.0)
        self._check_ratios()

    def _check_ratios(self) -> None:
        """The hard limits of :data:`LIMITS` on h/w, l/w, t0/w and w̄/w, each error naming the
        parameter over w, the ratio and the allowed range in mm."""
        w = self.w
        for key, num, name in (("h/w", self.h, "h"), ("l/w", self.l, "l"), ("t0/w", self.t0, "t0")):
            lo, hi = LIMITS[key]
            r = num / w
            below_hi = r < hi if key == "t0/w" else r <= hi
            if not (lo <= r and below_hi):
                top = "<" if key == "t0/w" else "<="
                raise ParameterError(name, num, f"{lo * w:.4g} to {hi * w:.4g} mm "
                                     f"({lo:g} <= {key} {top} {hi:g} for w = {w:g} mm)")
        ratio = self.w_bar / w
        if not ratio <= LIMITS["w_bar/w"]:
            raise ParameterError("cy", self.cy, f"a bulge whose widest half-width w̄ = w / "
                                 f"sin(Δu)^(2/n1) (eqs. 12, 14) is <= {LIMITS['w_bar/w']:g} w "
                                 f"(here {ratio:.3g} w with n1 = {self.n1:g}, n2 = {self.n2:g})")

    # -- derived quantities, eqs. 12–14 -------------------------------------------------------
    @property
    def delta_u(self) -> float:
        """Δu = arccos(|−c_y|^(n2/2)) (eq. 12), rad."""
        return math.acos(min(1.0, abs(self.cy) ** (self.n2 / 2)))

    @property
    def h_bar(self) -> float:
        """h̄ = h / (1 + c_y) (eq. 13), mm."""
        return self.h / (1.0 + self.cy)

    @property
    def w_bar(self) -> float:
        """w̄ = w / sin(Δu)^(2/n1) (eq. 14), mm: the largest half-width of the cavity."""
        s = math.sin(self.delta_u)
        return self.w / s ** (2.0 / self.n1) if s > 0 else math.inf

    @property
    def z_widest(self) -> float:
        """Height c_y·h̄ (mm) of the widest section, where Type D's slope g changes sign."""
        return self.cy * self.h_bar

    def replace(self, **changes) -> "SPSCGeometry":
        return replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return {k: getattr(self, k) for k in PARAMS}

    def design_space_warnings(self) -> list[str]:
        """Messages for each ratio outside the verified design space (empty if inside)."""
        values = {"n1": self.n1, "n2": self.n2, "cy": self.cy, "h/w": self.h / self.w,
                  "l/w": self.l / self.w, "t0/w": self.t0 / self.w}
        out = []
        for key, (lo, hi) in DESIGN_SPACE.items():
            v = values[key]
            if not (lo - 1e-12 <= v <= hi + 1e-12):
                out.append(f"{key} = {v:.4g} is outside the verified design space [{lo:g}, {hi:g}]")
        return out

    # -- the profile, eqs. 10–11 --------------------------------------------------------------
    def profile(self, u):
        """Super-ellipse point (X, Y) in mm at angle ``u`` from +j, clockwise (eqs. 10–11).

        ``u ∈ [0, π − Δu]`` runs from the apex (0, h) to the clamped edge (w, 0).
        """
        u = np.asarray(u, dtype=float)
        s, c = np.sin(u), np.cos(u)
        X = self.w_bar * np.abs(s) ** (2.0 / self.n1) * np.sign(s)
        Y = self.h_bar * (np.abs(c) ** (2.0 / self.n2) * np.sign(c) + self.cy)
        return X, Y

    def radius_at(self, z):
        """Cavity half-width r(z) in mm at height z ∈ [0, h] (the profile solved for x)."""
        z = np.asarray(z, dtype=float)
        s = np.abs(z / self.h_bar - self.cy)
        return self.w_bar * np.clip(1.0 - s**self.n2, 0.0, None) ** (1.0 / self.n1)

    def outward_normal(self, x, z):
        """Unit outward normal of the profile at its point (x, z): the gradient of
        (x/w̄)^n1 + |z/h̄ − c_y|^n2, normalised (well defined where eq. 16 is infinite)."""
        x = np.asarray(x, dtype=float)
        s = np.asarray(z, dtype=float) / self.h_bar - self.cy
        gx = self.n1 * np.abs(x / self.w_bar) ** (self.n1 - 1) / self.w_bar
        # one-sided at s = 0: the point belongs to the upper branch (matters only for n2 = 1)
        gz = self.n2 * np.abs(s) ** (self.n2 - 1) * np.where(s >= 0, 1.0, -1.0) / self.h_bar
        norm = np.hypot(gx, gz)
        return gx / norm, gz / norm

    # -- the meridian for the membrane solver, eqs. 15–16 -------------------------------------
    def meridian(self, x, upper: bool = True):
        """Undeformed meridian y(x) in mm (eq. 15).

        ``upper=True``: the branch y ≥ c_y·h̄ (0 ≤ x ≤ w̄); ``upper=False``: Type D's lower branch
        y < c_y·h̄ (w ≤ x ≤ w̄), y = h̄[c_y − (1 − (x/w̄)^n1)^(1/n2)] (the ± on the root only).
        """
        root = np.clip(1.0 - (np.asarray(x, dtype=float) / self.w_bar) ** self.n1, 0.0, None)
        root = root ** (1.0 / self.n2)
        return self.h_bar * (self.cy + root) if upper else self.h_bar * (self.cy - root)

    def slope(self, x, upper: bool = True):
        """Meridian slope g(x) = dy/dx (eq. 16): minus sign on the upper branch, plus below.

        Infinite at x = w̄ (and at x = w for Types A, B); callers integrating in x must avoid it.
        """
        xi = np.asarray(x, dtype=float) / self.w_bar
        with np.errstate(divide="ignore"):
            mag = (self.h_bar / self.w_bar) * (self.n1 / self.n2) * xi ** (self.n1 - 1) * (
                np.clip(1.0 - xi**self.n1, 0.0, None) ** (1.0 / self.n2 - 1.0))
        return -mag if upper else mag

    # -- analytic cavity volume ---------------------------------------------------------------
    def cavity_volume(self) -> float:
        """Nominal cavity volume V_b,i in mm³: revolved ends plus extruded middle,

        V = ∫₀ʰ [π r(z)² + 2 l r(z)] dz,

        in closed form (:func:`spsc.cad.cavity.cavity_volumes`), which reproduces Table 1
        (A 4.96, B 4.09, C 3.04, D 6.50 cm³).
        """
        from .cavity import cavity_volumes

        return float(cavity_volumes(self.w, self.h, self.l, self.n1, self.n2, self.cy))

    # -- polylines for the CAD --------------------------------------------------------------------
    def profile_points(self, n: int = 121) -> tuple[np.ndarray, np.ndarray]:
        """``n`` points (x, z) of the cavity profile from the apex (0, h) to the edge (w, 0) and
        their unit outward normals, spaced evenly in the arc length of the offset curve
        (ds + t0·dθ), so both the profile and its offset by t0 are resolved where they bend.
        Points closer than 1e-6·w are merged."""
        u = _dense_u(self)
        X, Y = self.profile(u)
        X[0], Y[0], X[-1], Y[-1] = 0.0, self.h, self.w, 0.0
        nx, nz = self.outward_normal(X, Y)
        nx[0], nz[0] = 0.0, 1.0
        theta = np.arctan2(nz, nx)
        if np.abs(np.diff(theta)).max() >= math.pi:  # nx >= 0: never, np.unwrap a no-op
            theta = np.unwrap(theta)
        ds = np.hypot(np.diff(X), np.diff(Y)) + self.t0 * np.abs(np.diff(theta))
        s = np.concatenate([[0.0], np.cumsum(ds)])
        keep = np.concatenate([[True], np.diff(s) > 0])
        u_n = np.interp(np.linspace(0.0, s[-1], n), s[keep], u[keep])
        X, Y = self.profile(u_n)
        X[0], Y[0], X[-1], Y[-1] = 0.0, self.h, self.w, 0.0
        nx, nz = self.outward_normal(X, Y)
        nx[0], nz[0] = 0.0, 1.0
        pts, nrm = np.column_stack([X, Y]), np.column_stack([nx, nz])
        keep = _distinct(pts, 1e-6 * self.w)
        return pts[keep], nrm[keep]

    @property
    def has_corner(self) -> bool:
        """The profile has a corner at its widest point (w̄, c_y·h̄): n2 = 1 with 0 < c_y·h̄ < h
        (the upper and lower branches meet there at an angle)."""
        return self.n2 <= 1.0 and 0.0 < self.z_widest < self.h

    def _with_corner(self, pts, nrm):
        """``pts``, ``nrm`` with the corner point (w̄, c_y·h̄) in its place twice, with the upper
        branch's normal and then the lower's (near samples of it dropped): the turn of the
        normal that :func:`_fan_corners` fills with an arc."""
        corner = np.array([self.w_bar, self.z_widest])
        up = np.array(self.outward_normal(corner[0], corner[1]), dtype=float)
        low = up * np.array([1.0, -1.0])  # the lower branch's one-sided normal
        near = np.hypot(*(pts - corner).T) <= 1e-6 * self.w
        k = int(np.searchsorted(-pts[:, 1], -corner[1]))  # apex first: z decreasing
        pts = np.vstack([pts[:k][~near[:k]], corner, corner, pts[k:][~near[k:]]])
        nrm = np.vstack([nrm[:k][~near[:k]], up, low, nrm[k:][~near[k:]]])
        return pts, nrm

    def outer_profile_points(self, n: int = 121) -> np.ndarray:
        """The outer wall surface: the profile offset by t0 along its normal, from (0, h + t0)
        down to the base plane z = 0. Where the offset ends above z = 0 (Type C) it is prolonged
        along its end tangent; where it dips below (Type D) it is cut there (docs/design.md)."""
        return self.wall_profiles(n)[1]

    def wall_profiles(self, n: int = 121) -> tuple[np.ndarray, np.ndarray]:
        """The cavity profile of :meth:`profile_points` and the outer wall of
        :meth:`outer_profile_points` (points (x, z) in mm, apex first) from one evaluation."""
        inner, nrm = self.profile_points(n)
        pts = inner
        if self.has_corner:  # both normals at the corner, for the offset's arc
            pts, nrm = self._with_corner(inner, nrm)
        pts, nrm = _fan_corners(pts, nrm)
        off = pts + self.t0 * nrm
        below = np.nonzero(off[:, 1] < 0.0)[0]
        if below.size:
            k = below[0]
            a, b = off[k - 1], off[k]
            f = a[1] / (a[1] - b[1])
            end = a + f * (b - a)
            end[1] = 0.0
            off = np.vstack([off[:k], end])
            if np.hypot(*(off[-1] - off[-2])) < 1e-6:
                off = np.delete(off, -2, axis=0)
        elif off[-1, 1] > 1e-9:
            t = off[-1] - off[-2]
            t /= np.hypot(*t)
            end = off[-1] + t * (off[-1, 1] / -t[1])
            end[1] = 0.0
            off = np.vstack([off, end])
        else:
            off[-1, 1] = 0.0
        return inner, off[_distinct(off, 1e-6 * self.w)]


def _distinct(pts: np.ndarray, tol: float) -> np.ndarray:
    """Mask keeping the first and last point and every point farther than ``tol`` from the last
    kept one (near-coincident points break spline interpolation, e.g. c_y → 0 with n2 = 1)."""
    keep = np.ones(len(pts), dtype=bool)
    step = np.hypot(*np.diff(pts[:-1], axis=0).T)
    to_end = np.hypot(*(pts[-1] - pts[1:-1]).T)
    if np.all(step > tol) and np.all(to_end > tol):
        return keep  # nothing to drop: the usual case, without the walk below
    keep[1:-1] = False
    last = pts[0]
    for i in range(1, len(pts) - 1):
        if np.hypot(*(pts[i] - last)) > tol and np.hypot(*(pts[-1] - pts[i])) > tol:
            keep[i], last = True, pts[i]
    return keep


def _fan_corners(pts, nrm, max_turn=math.radians(3.0)):
    """Where the normal jumps between two coincident points (a corner of the profile, n2 = 1 with
    c_y > 0), insert normals sweeping the gap, so the offset is a round arc and not a chord."""
    turn = np.abs(np.diff(np.arctan2(nrm[:, 1], nrm[:, 0])))
    gap = np.hypot(*np.diff(pts, axis=0).T)
    if not np.any((turn > 0.99 * max_turn) & (gap < 1.01e-3 * np.maximum(1.0, turn))):
        return pts.copy(), nrm.copy()  # no corner: the usual case, without the walk below
    out_p, out_n = [pts[0]], [nrm[0]]
    for k in range(1, len(pts)):
        a0, a1 = math.atan2(nrm[k - 1, 1], nrm[k - 1, 0]), math.atan2(nrm[k, 1], nrm[k, 0])
        turn = a1 - a0
        if abs(turn) > max_turn and np.hypot(*(pts[k] - pts[k - 1])) < 1e-3 * max(1.0, abs(turn)):
            for a in a0 + turn * np.linspace(0, 1, int(abs(turn) / max_turn) + 2)[1:-1]:
                out_p.append(pts[k])
                out_n.append(np.array([math.cos(a), math.sin(a)]))
        out_p.append(pts[k])
        out_n.append(nrm[k])
    return np.array(out_p), np.array(out_n)


#: the offsets of :func:`_dense_u`'s clustered points from where a derivative is infinite
_CLUSTER = np.geomspace(1e-12, 0.2, 600)


def _dense_u(g: SPSCGeometry) -> np.ndarray:
    """A dense parameter grid on [0, π − Δu], clustered geometrically where X(u) or Y(u) have
    infinite derivative (u = 0, u = π/2) so power-law ends are resolved."""
    umax = math.pi - g.delta_u
    d = _CLUSTER
    parts = [np.linspace(0.0, umax, 6001), d]
    if umax > math.pi / 2:
        parts += [math.pi / 2 - d, math.pi / 2 + d]
    else:
        parts.append(umax - d)
    u = np.concatenate(parts)
    return np.unique(np.clip(u, 0.0, umax))


def preset(type_name: str, size: str = "table1", **overrides) -> SPSCGeometry:
    """Geometry of a notable type, ``A`` … ``D``, at footprint ``table1`` (w = 11, h = 13, l = 3,
    t0 = 1 mm) or ``GS1`` (w = h = l = 10, t0 = 1 mm); keyword overrides replace any parameter."""
    key = str(type_name).strip().upper()
    if key not in TYPES:
        raise ParameterError("type", type_name, "one of " + ", ".join(TYPES))
    sizes = {k.lower(): v for k, v in SIZES.items()}
    if str(size).lower() not in sizes:
        raise ParameterError("size", size, "one of " + ", ".join(SIZES))
    w, h, l, t0 = sizes[str(size).lower()]
    n1, n2, cy = TYPES[key]
    params = dict(w=w, h=h, l=l, t0=t0, n1=n1, n2=n2, cy=cy)
    unknown = set(overrides) - set(params)
    if unknown:
        name = sorted(unknown)[0]
        raise ParameterError(name, overrides[name], "a parameter among w, h, l, t0, n1, n2, cy")
    params.update({k: v for k, v in overrides.items() if v is not None})
    return SPSCGeometry(**params)
