"""Two geometry kernels behind one small interface, so one mold recipe (:mod:`spsc.cad.mold.build`)
builds both the triangle meshes (manifold3d: the mold gate, STL and 3MF, exact control of every
tolerance as in :mod:`spsc.cad.meshbuild`) and the exact B-rep (OCCT through cadquery: the STEP a
CAD user edits). Lengths in mm; a ``frame`` is a 3x3 rotation whose columns are the parting
plane's u, v axes and its normal n, with ``origin`` on the plane.
"""

from __future__ import annotations

import cadquery as cq
import manifold3d as m3
import numpy as np

from ..bladder import bladder_breps
from ..meshbuild import _cylinder, bladder_solids
from ..specs import BladderSpec

__all__ = ["MeshKernel", "BrepKernel", "frame"]


class MeshKernel:
    """manifold3d solids."""

    name = "mesh"

    def bladder(self, spec: BladderSpec) -> dict:
        s = bladder_solids(spec)
        return {"body": s.body, "cavity": s.cavity, "bore": s.bore, "holes": s.holes}

    def box(self, lo, hi):
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        return m3.Manifold.cube((hi - lo).tolist()).translate(lo.tolist())

    def cylinder(self, radius, height, start, direction, r_top=None):
        return _cylinder(radius, height, start, direction, r_top=r_top)

    def sphere(self, radius, centre):
        from ..meshbuild import _segments

        return m3.Manifold.sphere(radius, _segments(radius)).translate(
            [float(c) for c in centre])

    def prism(self, ring, depth, frame, origin):
        """The simple polygon ``ring`` ((u, v), mm) extruded from the plane along −n by
        ``depth``."""
        cs = m3.CrossSection([np.asarray(ring, float).tolist()])
        solid = m3.Manifold.extrude(cs, depth).translate([0.0, 0.0, -depth])
        return _place(solid, frame, origin)

    def union(self, solids):
        solids = [s for s in solids if s is not None]
        return m3.Manifold.batch_boolean(solids, m3.OpType.Add) if len(solids) > 1 else solids[0]

    def cut(self, a, tools):
        tools = [t for t in tools if t is not None]
        return a - self.union(tools) if tools else a

    def intersect(self, a, b):
        return a ^ b

    def scale(self, a, k):
        return a.scale([k, k, k])

    def volume(self, a) -> float:
        return float(a.volume())


class BrepKernel:
    """cadquery (OCCT) solids."""

    name = "brep"

    def bladder(self, spec: BladderSpec) -> dict:
        return bladder_breps(spec)

    def box(self, lo, hi):
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        d = hi - lo
        return cq.Solid.makeBox(*d.tolist(), cq.Vector(*lo.tolist()))

    def cylinder(self, radius, height, start, direction, r_top=None):
        s, d = cq.Vector(*map(float, start)), cq.Vector(*map(float, direction))
        if r_top is None or abs(r_top - radius) < 1e-12:
            return cq.Solid.makeCylinder(radius, height, s, d)
        return cq.Solid.makeCone(radius, r_top, height, s, d)

    def sphere(self, radius, centre):
        return cq.Solid.makeSphere(radius, cq.Vector(*map(float, centre)), angleDegrees1=-90,
                                   angleDegrees2=90)

    def prism(self, ring, depth, frame, origin):
        w = cq.Wire.makePolygon([cq.Vector(float(u), float(v), 0.0) for u, v in ring],
                                close=True)
        solid = cq.Solid.extrudeLinear(cq.Face.makeFromWires(w), cq.Vector(0, 0, -depth))
        return _place_brep(solid, frame, origin)

    def union(self, solids):
        solids = [s for s in solids if s is not None]
        return solids[0].fuse(*solids[1:]).clean() if len(solids) > 1 else solids[0]

    def cut(self, a, tools):
        tools = [t for t in tools if t is not None]
        return a.cut(*tools).clean() if tools else a

    def intersect(self, a, b):
        return a.intersect(b).clean()

    def scale(self, a, k):
        return a.scale(k)

    def volume(self, a) -> float:
        return float(a.Volume())


def _place(solid: m3.Manifold, frame, origin) -> m3.Manifold:
    """Map plane coordinates (u, v, n) to part coordinates."""
    R = np.asarray(frame, float)
    m = np.hstack([R, np.asarray(origin, float).reshape(3, 1)])
    return solid.transform(m.tolist())


def _place_brep(solid, frame, origin):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf

    R, o = np.asarray(frame, float), np.asarray(origin, float)
    t = gp_Trsf()
    t.SetValues(*(float(x) for row in np.hstack([R, o.reshape(3, 1)]) for x in row))
    return cq.Shape.cast(BRepBuilderAPI_Transform(solid.wrapped, t, True).Shape())


def frame(normal: str) -> np.ndarray:
    """The parting plane's frame: ``z`` → (u, v, n) = (x, y, z); ``x`` → (y, z, x)."""
    if normal == "z":
        return np.eye(3)
    return np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])

