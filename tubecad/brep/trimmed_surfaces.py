"""Each face's B-spline surface cut down to the face (issue 44): a STEP file writes every face's
whole surface, so faces that each carry a large surface of which they use a corner make a
large file.

OCCT's conversion of an offset face to a B-spline (``ShapeCustom::ConvertToBSpline``, in
:func:`tubecad.design.net.hollow`) approximates the whole offset surface for every face: on the
ellipsoid's hollow wall 85 x 67 poles a face, 18 MB for a 3 x 3 net. :func:`segment_to_faces`
cuts each such surface to its face's parameter box (``Geom_BSplineSurface::Segment``: exact,
the parameters unchanged, so every pcurve stays valid), in place (the edges keep their
pcurves against that very surface). A surface two faces share is left whole.
"""

from __future__ import annotations

from OCP.BRep import BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_BSplineSurface
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS_Shape

from tubecad.occ_compat import as_face

#: the margin round the face's parameter box, as a share of the surface's parameter range
MARGIN = 1e-9


def segment_to_faces(shape: TopoDS_Shape) -> int:
    """Cut, in place, each B-spline surface of ``shape`` used by one face only to that face's
    parameter box (module docstring); returns how many were cut.

    Args:
        shape: a shape whose faces' surfaces may be cut (changed in place).

    Returns:
        The number of surfaces cut.
    """
    faces, surfaces = [], []
    walk = TopExp_Explorer(shape, TopAbs_FACE)
    while walk.More():
        face = as_face(walk.Current())
        faces.append(face)
        surfaces.append(BRep_Tool.Surface_s(face))  # OCP hands a shared surface out as one object
        walk.Next()
    cut = 0
    for face, surface in zip(faces, surfaces):
        if not isinstance(surface, Geom_BSplineSurface) or sum(other is surface for other in surfaces) > 1:
            continue
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        low_u, high_u, low_v, high_v = surface.Bounds()
        du, dv = MARGIN * (high_u - low_u), MARGIN * (high_v - low_v)
        if u0 < low_u - du or u1 > high_u + du or v0 < low_v - dv or v1 > high_v + dv:
            continue  # across a periodic surface's seam: left whole
        box = (max(low_u, u0 - du), min(high_u, u1 + du), max(low_v, v0 - dv), min(high_v, v1 + dv))
        if box == (low_u, high_u, low_v, high_v):
            continue
        surface.Segment(*box)
        cut += 1
    return cut
