"""Solids for the printability-gate tests (manifold3d): a hollow sphere with a bore, its port
plug, and STL writing."""

from __future__ import annotations

import math

import manifold3d as mf
import numpy as np
import trimesh

from spsc.cad import meshtopo

__all__ = ["M", "R_OUT", "R_IN", "BORE", "arrays", "bladder", "port_design",
           "face_plane_radius", "write_stl"]

M = mf.Manifold
R_OUT, R_IN, BORE = 12.0, 11.0, 1.5


def arrays(solid: mf.Manifold):
    g = solid.to_mesh64()
    return np.asarray(g.vert_properties)[:, :3].copy(), np.asarray(g.tri_verts).astype(np.int64)


def bladder(r_out=R_OUT, r_in=R_IN, n=64, bore=BORE, shift=(0.0, 0.0, 0.0), bore_n=32):
    """Hollow sphere (cavity centred on the origin) with a bore through its bottom."""
    solid = M.sphere(r_out, n).translate(shift) - M.sphere(r_in, n)
    if bore:
        solid = solid - M.cylinder(r_out + 2, bore, bore, bore_n).translate((0, 0, -(r_out + 2)))
    return solid


def port_design(r_out=R_OUT, r_in=R_IN, bore=BORE, **extra):
    """Plug from below the port tip up to where the bore meets the (analytic) cavity sphere."""
    z1 = -math.sqrt(r_in**2 - bore**2)
    return {"port": {"axis_point": [0, 0, 0], "axis_dir": [0, 0, -1], "radius": bore,
                     "z_range": [-(r_out + 1), z1]}, **extra}


def face_plane_radius(v, f, inner: bool) -> float:
    """Smallest distance from the origin to the plane of a face of the inner (or outer) sphere
    of a hollow sphere: the inscribed polyhedron holds the ball of that radius."""
    sel = (np.linalg.norm(v[f], axis=2).max(axis=1) < (R_IN + R_OUT) / 2) == inner
    n = meshtopo.face_normals(v, f[sel])
    return float(np.abs(np.einsum("ij,ij->i", n, v[f[sel, 0]])).min())


def write_stl(path, solid_or_arrays, ascii=False):
    v, f = solid_or_arrays if isinstance(solid_or_arrays, tuple) else arrays(solid_or_arrays)
    trimesh.Trimesh(v, f, process=False).export(path, file_type="stl_ascii" if ascii else "stl")
    return path
