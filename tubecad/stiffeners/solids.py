"""Stiffener solids standing on a wall along its curvature lines (issue 4).

Ring frame at s_i: the slice of the wall's tube between the normal planes at
s_i -+ t/2, between radii R and R + h (outside) or R - h and R (inside): a planar ring
whose side faces are annuli in normal planes and whose base *is* the wall surface, so it
meets the wall with no gap. A T or L flange is a second slice, fused on.

Stringer at angle theta: the profile outline swept with the rotation-minimising frame,
P(w, v; s) = C(s) + v N(s) + w E(s) with N = cos th R1 + sin th R2 (the surface normal
along the line) and E = -sin th R1 + cos th R2. Each outline edge is a ruled B-spline
face whose poles are affine combinations of the frame spline's poles (as exact as the
wall). Its base is the wall surface patch between the angles th -+ asin(t / 2R), so the
web's side faces start exactly on the wall. Faces are sewn into a closed solid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import build123d as bd
import numpy as np
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon, BRepBuilderAPI_MakeSolid,
    BRepBuilderAPI_MakeWire, BRepBuilderAPI_Sewing,
)  # fmt: skip
from OCP.BRepLib import BRepLib
from OCP.Geom import Geom_BSplineSurface
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_SHELL
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from ..brep import NetLayout, build_wall_solid
from ..brep.solids import orthogonality_for
from ..errors import ParameterError, TubecadError
from ..fitting import exact_section_surface, fit_frame
from ..fitting.occ_arrays import integers, knots_and_multiplicities, points_2d, reals
from ..surface import CurvatureLineTube
from .profiles import SIDES, Profile

SEWING_TOLERANCE = 1e-6


@dataclass
class Stiffener:
    """A named stiffener solid and what it stands on."""

    name: str  # ring_03, stringer_05
    kind: str  # ring | stringer
    value: float  # s of a ring, angle (deg) of a stringer
    solid: bd.Solid
    profile: Profile
    side: str
    base: CurvatureLineTube  # the wall surface it stands on, over its own span

    @property
    def base_radius(self) -> float:
        return self.base.radius

    def length(self) -> float:
        """Length of its line on the wall: 2 pi R for a ring; Int sqrt(G) ds along u = angle
        for a stringer (Gauss-Legendre on the exact G = (1 - R k cos phi)^2)."""
        if self.kind == "ring":
            return 2 * math.pi * self.base.radius
        x, w = np.polynomial.legendre.leggauss(32)
        edges = np.linspace(*self.base.span, 33)
        s = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * x).ravel()
        g = self.base.fundamental_forms(math.radians(self.value), s).G
        return float((np.sqrt(g) * np.tile(w, 32) * np.repeat(0.5 * np.diff(edges), 32)).sum())


def ring_stiffener(tube: CurvatureLineTube, s: float, profile: Profile, side: str = "outside",
                   tolerance: float = 1e-8, name: str = "ring") -> Stiffener:  # fmt: skip
    """The ring frame at ``s`` on the tube of radius R = tube.radius (the wall's face it stands on)."""
    _check_side(side)
    R = tube.radius
    if side == "inside" and not profile.height < R:
        raise ParameterError(f"height must be < R = {R:g} for an inside stiffener, got {profile.height:g}")
    webtop = profile.height - (profile.flange_thickness if profile.kind != "flat" else 0.0)
    tw = profile.thickness
    web = _slice(tube, (s - tw / 2, s + tw / 2), webtop, side, tolerance)
    if profile.kind != "flat":
        start = s - profile.flange_width / 2 if profile.kind == "T" else s - tw / 2
        flange = _slice(tube, (start, start + profile.flange_width), profile.flange_thickness, side, tolerance,
                        offset=webtop)  # fmt: skip
        web = web.fuse(flange).clean()
        if not isinstance(web, bd.Solid):
            web = web.solids()[0]
    return Stiffener(name, "ring", float(s), web, profile, side, CurvatureLineTube(tube.axis, R, allow_irregular=True))


def _slice(tube: CurvatureLineTube, span: tuple[float, float], height: float, side: str, tolerance: float,
           offset: float = 0.0) -> bd.Solid:  # fmt: skip
    lo, hi = tube.span
    a, b = max(span[0], lo), min(span[1], hi)
    if not b > a:
        raise ParameterError(f"ring at s in [{span[0]:g}, {span[1]:g}] lies outside the span [{lo:g}, {hi:g}]")
    sign = 1.0 if side == "outside" else -1.0
    base = tube.radius + sign * offset
    sub = CurvatureLineTube(tube.axis.restricted((a, b)), base, allow_irregular=True)
    build = build_wall_solid(sub, height, side, NetLayout.equal(sub, 2, 4), tolerance)
    return build.shape


def stringer_stiffener(tube: CurvatureLineTube, theta_deg: float, profile: Profile, side: str = "outside",
                       span: tuple[float, float] | None = None, tolerance: float = 1e-8,
                       name: str = "stringer") -> Stiffener:  # fmt: skip
    """The stringer at angle ``theta_deg`` on the tube of radius R = tube.radius, over ``span``."""
    _check_side(side)
    R, sign = tube.radius, (1.0 if side == "outside" else -1.0)
    tw = profile.thickness
    if not tw < 2 * R:
        raise ParameterError(f"thickness must be < 2 R = {2 * R:g}, got {tw:g}")
    if side == "inside" and not profile.height < R:
        raise ParameterError(f"height must be < R = {R:g} for an inside stiffener, got {profile.height:g}")
    axis = tube.axis.restricted(span) if span else tube.axis
    s0, s1 = axis.span
    frame = fit_frame(axis, R + profile.height, tolerance, orthogonality_for(tolerance))
    theta = math.radians(theta_deg)
    delta = math.asin(tw / (2 * R))

    def radial(h: float) -> float:  # distance from the axis along N of an outline corner
        return R * math.cos(delta) if h == 0.0 else R + sign * h

    corners = [(w, radial(h)) for w, h in profile.outline()]
    faces = [BRepBuilderAPI_MakeFace(ruled_surface(frame, theta, p, q), 0.0, 1.0, s0, s1, 1e-7).Face()
             for p, q in zip(corners[:-1], corners[1:])]  # fmt: skip
    base_tube = CurvatureLineTube(axis, R, allow_irregular=True)
    base = exact_section_surface(base_tube, frame, origin_deg=math.degrees(theta - delta))
    u1 = float(base.u_at(math.degrees(theta + delta)))
    faces.append(BRepBuilderAPI_MakeFace(base.surface, 0.0, u1, s0, s1, 1e-7).Face())
    faces += [_cap(frame.spline(s), theta, corners, base, s, u1) for s in (s0, s1)]
    return Stiffener(name, "stringer", float(theta_deg), sew_solid(faces, name), profile, side, base_tube)


def ruled_surface(frame, theta: float, p: tuple[float, float], q: tuple[float, float]) -> Geom_BSplineSurface:
    """The ruled face from corner p = (w, v) to q in the cross-section plane, swept along s:
    poles C_j + v N_j + w E_j (degree 1 across, the frame spline's knots along s), with
    N = cos th R1 + sin th R2 and E = -sin th R1 + cos th R2."""
    F = frame.spline.c
    C, R1, R2 = F[:, :3], F[:, 3:6], F[:, 6:]
    N = math.cos(theta) * R1 + math.sin(theta) * R2
    E = -math.sin(theta) * R1 + math.cos(theta) * R2
    poles = np.stack([C + p[1] * N + p[0] * E, C + q[1] * N + q[0] * E])
    s_knots, s_mults = knots_and_multiplicities(frame.spline.t)
    return Geom_BSplineSurface(points_2d(poles), reals([0.0, 1.0]), reals(s_knots), integers([2, 2]),
                               integers(s_mults), 1, frame.degree)  # fmt: skip


def sew_solid(faces, name: str) -> bd.Solid:
    """Sew faces that meet along common edges (within 1e-6) into one closed solid."""
    sewing = BRepBuilderAPI_Sewing(SEWING_TOLERANCE)
    for face in faces:
        sewing.Add(face)
    sewing.Perform()
    explorer = TopExp_Explorer(sewing.SewedShape(), TopAbs_SHELL)
    if not explorer.More():
        raise TubecadError(f"{name}: its faces did not sew into a shell")
    solid = BRepBuilderAPI_MakeSolid(TopoDS.Shell_s(explorer.Current())).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    return bd.Solid(solid)


def _cap(F: np.ndarray, theta: float, corners: list[tuple[float, float]], base, s: float, u1: float):
    """Planar end face in the normal plane at s: the outline's straight edges, then the base
    arc (from the -w corner at u = 0 back to the +w corner at u1)."""
    c, r1, r2 = F[:3], F[3:6], F[6:]
    n = math.cos(theta) * r1 + math.sin(theta) * r2
    e = -math.sin(theta) * r1 + math.cos(theta) * r2
    polygon = BRepBuilderAPI_MakePolygon()
    for w, v in corners:
        polygon.Add(gp_Pnt(*map(float, c + v * n + w * e)))
    wire = BRepBuilderAPI_MakeWire(polygon.Wire())
    wire.Add(BRepBuilderAPI_MakeEdge(base.surface.VIso(s), 0.0, u1).Edge())
    if not wire.IsDone():
        raise TubecadError(f"the end face of a stringer stiffener at s = {s:g} could not be closed")
    return BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()


def web_face(base: CurvatureLineTube, theta_deg: float, height: float, side: str = "outside",
             tolerance: float = 1e-8) -> bd.Face:  # fmt: skip
    """The web's mid-surface along the stringer at ``theta_deg``: the strip of surface normals
    from the wall (radius R) to R +- height, a ruled B-spline face on the frame fit."""
    _check_side(side)
    R, sign = base.radius, (1.0 if side == "outside" else -1.0)
    frame = fit_frame(base.axis, R + height, tolerance, orthogonality_for(tolerance))
    surface = ruled_surface(frame, math.radians(theta_deg), (0.0, R), (0.0, R + sign * height))
    return bd.Face(BRepBuilderAPI_MakeFace(surface, 0.0, 1.0, *base.span, 1e-7).Face())


def _check_side(side: str) -> None:
    if side not in SIDES:
        raise ParameterError(f"side must be one of {', '.join(SIDES)}, got {side!r}")
