"""The lower surfaces of the rigid bodies that press a chamber (:mod:`.indenter`), as height
functions of the lateral position: S (mm above the tip), its gradient and its Hessian, for
the contact's constraint and its curvature (:mod:`spsc.fem.engine.leaning`)."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["across", "round_", "tilted", "wedge", "cone"]


def across(lateral, axis: str, profile):
    """A body constant along the x or y ``axis``: its ``profile`` of the coordinate across
    it, as (S, ∇S, ∇²S) in the plane (k = 2)."""
    n = lateral.shape[1]
    across = 1 if axis == "x" else 0  # the coordinate across the axis
    S, dS, d2S = profile(lateral[across:across + 1])
    grad, hess = np.zeros((2, n)), np.zeros((2, 2, n))
    grad[across] = dS.reshape(n)
    hess[across, across] = d2S.reshape(n)
    return S, grad, hess


def round_(p, R):
    """A sphere (k = 2 or 1) or a cylinder (one coordinate) of radius R (n,) about p = 0:
    S = R − √(R² − |p|²), evaluated as |p|² / (R + √(R² − |p|²)) (no cancellation for a
    large R)."""
    rho2 = np.sum(p * p, axis=0)
    inside = rho2 < R * R
    s = np.sqrt(np.where(inside, R * R - rho2, 1.0))
    S = np.where(inside, rho2 / (R + s), np.inf)
    grad = p / s
    k = p.shape[0]
    hess = np.eye(k)[:, :, None] / s + p[:, None, :] * p[None, :, :] / s ** 3
    return S, grad, hess


def tilted(p, tilt, axis, gap):
    """A plate turned by ``tilt`` (rad) about the x or y ``axis``: z = tip + tan(tilt) times
    the coordinate across the axis; offset by the gap along its normal, g / cos(tilt) below."""
    across = 1 if axis == "x" else 0
    n = p.shape[1]
    S = math.tan(tilt) * p[across] - gap * (1.0 / math.cos(tilt) - 1.0)
    grad = np.zeros((2, n))
    grad[across] = math.tan(tilt)
    return S, grad, np.zeros((2, 2, n))


def wedge(d, r, half):
    """A wedge of half-angle ``half`` (rad) whose edge is rounded with radius r (n,): the
    arc r − √(r² − d²) out to |d| = r cos(half), where it meets the flanks of slope
    cot(half) tangentially."""
    cot = 1.0 / math.tan(half)
    dt = r * math.cos(half)
    a = np.abs(d)
    arc = a < dt
    s = np.sqrt(np.where(arc, r * r - d * d, 1.0))
    S = np.where(arc, r - s, r * (1 - math.sin(half)) + (a - dt) * cot)
    grad = np.where(arc, d / s, np.sign(d) * cot)
    hess = np.where(arc, r * r / s ** 3, 0.0)
    return S, grad[None], hess[None, None]


def cone(p, r, half):
    """A cone of half-angle ``half`` (rad) about p = 0 (k = 2, or k = 1 the radius of an
    axisymmetric section), its tip a sphere of radius r (n,) out to ρ = r cos(half), where the
    flank of slope cot(half) meets it tangentially: S(ρ) as :func:`wedge`'s profile, its
    gradient S'(ρ) p/ρ and Hessian S'' p pᵀ/ρ² + S'/ρ (I − p pᵀ/ρ²)."""
    k, n = p.shape
    cot = 1.0 / math.tan(half)
    rho = np.sqrt(np.sum(p * p, axis=0))
    dt = r * math.cos(half)
    arc = rho < dt
    s = np.sqrt(np.where(arc, r * r - rho * rho, 1.0))
    S = np.where(arc, r - s, r * (1 - math.sin(half)) + (rho - dt) * cot)
    safe = np.where(rho > 0, rho, 1.0)
    unit = p / safe
    outer = unit[:, None, :] * unit[None, :, :]
    eye = np.eye(k)[:, :, None]
    # on the arc the sphere's own forms (smooth through ρ = 0); on the flank the cone's
    grad = np.where(arc, p / s, cot * unit)
    hess = np.where(arc, eye / s + p[:, None, :] * p[None, :, :] / s ** 3,
                    cot / safe * (eye - outer))
    return S, grad, hess
