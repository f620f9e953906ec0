"""The three host faces the samples ship as STEP (issue 44), made here from their defining
numbers so a test holds the shipped files to them (``cd tests && python -m shared.host_faces``
writes them again):

- ``samples/ellipsoid.step``: the triaxial ellipsoid 300 x 200 x 100 mm, OCCT's sphere
  converted to NURBS with its poles scaled (:func:`tests.shared.ellipsoid.nurbs_ellipsoid`),
  one closed face with its four umbilics (two on the seam);
- ``samples/dome.step``: a 2:1 elliptical head of radius 500 mm (semi-axes 500 and 250), the
  exact rational quarter ellipse revolved, cut at a crown opening of radius 100 mm (the pole,
  an umbilic of index 1, is not on the face): its lines are meridians and parallels;
- ``samples/hull_panel.step``: a bicubic B-spline bilge panel 4000 mm long, its section
  turning from the bottom to the side and narrowing forward (no umbilic on it).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

SAMPLES = Path(__file__).resolve().parents[2] / "samples"
ELLIPSOID = (300.0, 200.0, 100.0)
DOME = {"radius": 500.0, "height": 250.0, "opening": 100.0}
#: the hull panel's poles (6 along x by 5 round the bilge, mm) and its knots
HULL_X = (0.0, 800.0, 1600.0, 2400.0, 3200.0, 4000.0)


def hull_poles() -> np.ndarray:
    """(6, 5, 3) poles: the bilge section (the bottom from 0.45 of the half-breadth, the turn,
    the side flaring out up to z = 1100) of half-breadth ``b(x)`` narrowing forward and a
    bottom rising aft."""
    poles = np.empty((6, 5, 3))
    for i, x in enumerate(HULL_X):
        t = x / HULL_X[-1]
        breadth = 1500.0 - 450.0 * t * t  # narrowing forward
        rise = 120.0 * (1.0 - t) ** 2  # the bottom rising aft
        section = [  # (y, z) from the keel side of the panel up the flaring side
            (0.45 * breadth, rise),
            (0.8 * breadth, rise + 30.0),
            (breadth, rise + 250.0),
            (breadth + 80.0, rise + 650.0),
            (breadth + 200.0, 1100.0),
        ]
        for j, (y, z) in enumerate(section):
            poles[i, j] = (x, y, z)
    return poles


def hull_surface():
    """The bicubic B-spline hull panel (clamped uniform knots both ways)."""
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    from tubecad.occ_compat import Array1OfInteger, Array1OfReal, Array2OfPnt

    poles = hull_poles()
    net = Array2OfPnt(1, poles.shape[0], 1, poles.shape[1])
    for i in range(poles.shape[0]):
        for j in range(poles.shape[1]):
            net.SetValue(i + 1, j + 1, gp_Pnt(*(float(c) for c in poles[i, j])))

    def knots(values, mults):
        k, m = Array1OfReal(1, len(values)), Array1OfInteger(1, len(values))
        for n, (value, mult) in enumerate(zip(values, mults), 1):
            k.SetValue(n, float(value))
            m.SetValue(n, int(mult))
        return k, m

    uk, um = knots([0.0, 1 / 3, 2 / 3, 1.0], [4, 1, 1, 4])  # 6 poles, cubic
    vk, vm = knots([0.0, 0.5, 1.0], [4, 1, 4])  # 5 poles, cubic
    return Geom_BSplineSurface(net, uk, vk, um, vm, 3, 3)


def dome_surface():
    """The elliptical head: the quarter ellipse (rational quadratic B-spline) from the crown to
    the equator in the xz-plane, revolved about z."""
    from OCP.Geom import Geom_Ellipse, Geom_SurfaceOfRevolution, Geom_TrimmedCurve
    from OCP.GeomConvert import GeomConvert
    from OCP.gp import gp_Ax1, gp_Ax2, gp_Dir, gp_Pnt

    a, b = DOME["radius"], DOME["height"]
    ellipse = Geom_Ellipse(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, -1, 0), gp_Dir(1, 0, 0)), a, b)
    crown = float(np.arccos(DOME["opening"] / a))  # x = a cos t = the opening's radius
    meridian = GeomConvert.CurveToBSplineCurve_s(Geom_TrimmedCurve(ellipse, 0.0, crown))
    return Geom_SurfaceOfRevolution(meridian, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)))


def faces():
    """{file name: the build123d face} of the three samples."""
    import build123d as bd
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace

    from shared.ellipsoid import nurbs_ellipsoid

    out = {}
    ellipsoid = nurbs_ellipsoid(*ELLIPSOID)
    out["ellipsoid.step"] = bd.Face(BRepBuilderAPI_MakeFace(ellipsoid, 1e-7).Face())
    dome = dome_surface()
    u0, u1, v0, v1 = dome.Bounds()
    out["dome.step"] = bd.Face(BRepBuilderAPI_MakeFace(dome, u0, u1, v0, v1, 1e-7).Face())
    out["hull_panel.step"] = bd.Face(BRepBuilderAPI_MakeFace(hull_surface(), 1e-7).Face())
    return out


def write(folder: Path = SAMPLES) -> list[Path]:
    """Write the three STEP files into ``folder``."""
    import build123d as bd

    written = []
    for name, face in faces().items():
        face.label = Path(name).stem
        path = folder / name
        bd.export_step(face, path)
        written.append(path)
    return written


if __name__ == "__main__":
    for path in write():
        print(path)
