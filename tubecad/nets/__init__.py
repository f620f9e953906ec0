"""Curvature-line nets on the surfaces users already have (issue 44): any OCCT face or
surface read exactly (:mod:`~tubecad.nets.host`), its principal field
(:mod:`~tubecad.nets.principal`), its umbilics found and typed (:mod:`~tubecad.nets.umbilics`),
its lines of curvature traced (:mod:`~tubecad.nets.trace`) and made edges on it
(:mod:`~tubecad.nets.edges`), and the net of both families splitting the face into its patches
(:mod:`~tubecad.nets.net`)."""

from tubecad.nets.edges import LineEdge, line_edge
from tubecad.nets.host import HostSurface, SurfaceJet
from tubecad.nets.net import CurvatureNet, curvature_net
from tubecad.nets.principal import PrincipalField, principal_field
from tubecad.nets.trace import CurvatureLine, trace_line
from tubecad.nets.umbilics import Umbilic, Umbilics, find_umbilics

__all__ = [
    "CurvatureLine",
    "CurvatureNet",
    "HostSurface",
    "LineEdge",
    "PrincipalField",
    "SurfaceJet",
    "Umbilic",
    "Umbilics",
    "curvature_net",
    "find_umbilics",
    "line_edge",
    "principal_field",
    "trace_line",
]
