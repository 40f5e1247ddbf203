"""A clamped spherical dome as a closed part (manifold3d revolve): the shape of the part-FEM
tests, with the same chamber as an SPSCGeometry (w = h = r, l = 0, n1 = n2 = 2, c_y = 0) for
the structured mesh."""

from __future__ import annotations

import manifold3d as mf
import numpy as np

from spsc.cad.geometry import SPSCGeometry

__all__ = ["dome", "dome_geometry", "R_CAV", "T_WALL", "BASE"]

R_CAV, T_WALL, BASE = 6.0, 1.0, 1.5


def dome(r=R_CAV, t=T_WALL, base=BASE, seg=48, arc=12, bore=0.0):
    """(vertices, faces) of a hemispherical shell (cavity radius r, wall t) standing on a disc
    z ∈ [−base, 0] two mm wider, the cavity closed by the disc at z = 0; ``bore`` > 0 drills an
    inlet of that radius up the axis into the cavity (its port: :func:`dome_port`)."""
    ro = r + t
    a = np.linspace(0.0, np.pi / 2, arc + 1)
    pts = [(0.0, -base), (ro + 2, -base), (ro + 2, 0.0)]
    pts += [(ro * np.cos(x), ro * np.sin(x)) for x in a]
    pts += [(r * np.cos(x), r * np.sin(x)) for x in a[::-1]]
    pts += [(0.0, 0.0)]
    solid = mf.Manifold.revolve(mf.CrossSection([np.array([(max(x, 0.0), y) for x, y in pts])]),
                                seg)
    if bore:
        solid = solid - mf.Manifold.cylinder(base + 1.5, bore, bore, 24).translate((0, 0, -base - 1))
    m = solid.to_mesh64()
    return np.asarray(m.vert_properties)[:, :3].astype(float), np.asarray(m.tri_verts).astype(np.int64)


def dome_port(bore: float, base=BASE) -> dict:
    """The design file's port of :func:`dome`'s bore: plugged from below the part up to z = 0."""
    return {"axis_point": [0.0, 0.0, 0.0], "axis_dir": [0.0, 0.0, 1.0], "radius": bore,
            "z_range": [-base - 1.0, 0.0]}


def dome_geometry(r=R_CAV, t=T_WALL) -> SPSCGeometry:
    return SPSCGeometry(w=r, h=r, l=0.0, t0=t, n1=2.0, n2=2.0, cy=0.0)
