"""Curvature-line nets on the surfaces users already have (issue 44): any OCCT face or
surface read exactly (:mod:`~tubecad.nets.host`), its principal field
(:mod:`~tubecad.nets.principal`), its umbilics found and typed (:mod:`~tubecad.nets.umbilics`)
and its lines of curvature traced (:mod:`~tubecad.nets.trace`)."""

from tubecad.nets.host import HostSurface, SurfaceJet
from tubecad.nets.principal import PrincipalField, principal_field
from tubecad.nets.trace import CurvatureLine, trace_line
from tubecad.nets.umbilics import Umbilic, Umbilics, find_umbilics

__all__ = [
    "CurvatureLine",
    "HostSurface",
    "PrincipalField",
    "SurfaceJet",
    "Umbilic",
    "Umbilics",
    "find_umbilics",
    "principal_field",
    "trace_line",
]
