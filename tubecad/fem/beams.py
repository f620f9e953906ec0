"""Stiffeners as beam elements on the shell's nodes along their curvature lines.

A profile (flat, T, L: :class:`tubecad.stiffeners.profiles.Profile`) is a union of
rectangles in its own plane (w across, h up from the wall): the web w in [-t/2, t/2],
h in [0, H - t_f] (the whole H for a flat bar), and the flange of a T (w in [-b/2, b/2]) or
an L (w in [-t/2, b - t/2]), h in [H - t_f, H]. Each rectangle becomes one beam block
sharing the stiffener's nodes (CalculiX's rectangular section), with its centre offset
from the nodes: along the surface normal N by d + h_c (d: from the mesh's reference
surface to the wall face the stiffener stands on; h_c = +-(h0 + h1) / 2, minus inside), and
across by w_c. Beams whose sections share nodes add their axial and bending stiffness
about the node line exactly as the T or L would (plane sections stay plane); the torsion
constant adds up as the thin-walled approximation.

Beam axes: T the line's tangent, the 2-direction N, the 1-direction n1 = N x T. On a ring
n1 is the axis tangent t (w runs along +s), on a stringer -e_u (w runs along +e_u).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.stiffeners.profiles import Profile


@dataclass(frozen=True)
class Rectangle:
    """One rectangle of a profile: ``name`` (web, flange), w in [w0, w1], h in [h0, h1]."""

    name: str
    w0: float
    w1: float
    h0: float
    h1: float


def profile_rectangles(profile: Profile) -> list[Rectangle]:
    """The profile as rectangles (module docstring)."""
    tw, h = profile.thickness, profile.height
    if profile.kind == "flat":
        return [Rectangle("web", -tw / 2, tw / 2, 0.0, h)]
    hf, bf = h - profile.flange_thickness, profile.flange_width
    flange = (-bf / 2, bf / 2) if profile.kind == "T" else (-tw / 2, bf - tw / 2)
    return [Rectangle("web", -tw / 2, tw / 2, 0.0, hf), Rectangle("flange", *flange, hf, h)]


def clipped(rect: Rectangle, low: float, high: float) -> Rectangle | None:
    """``rect`` with w kept in [low, high] (a ring at the span's end: the part of its
    cross-section over the wall), or None if nothing is left."""
    w0, w1 = max(rect.w0, low), min(rect.w1, high)
    return (
        Rectangle(rect.name, w0, w1, rect.h0, rect.h1) if w1 - w0 > 1e-12 * max(1.0, abs(rect.w1 - rect.w0)) else None
    )


def section_centre(rect: Rectangle, base_offset: float, side: str, across: float) -> tuple[float, float]:
    """(along n1, along N) from the nodes to ``rect``'s centre: ``across`` = W . n1 (+-1)
    turns the profile's w into n1; ``base_offset`` is d, the wall face's distance from the
    reference surface along N."""
    sign = 1.0 if side == "outside" else -1.0
    return across * 0.5 * (rect.w0 + rect.w1), base_offset + sign * 0.5 * (rect.h0 + rect.h1)


def beam_directions(normals: np.ndarray, tangents: np.ndarray) -> np.ndarray:
    """n1 = N x T, unit, per element (rows)."""
    n1 = np.cross(normals, tangents)
    length = np.linalg.norm(n1, axis=-1, keepdims=True)
    if np.any(length < 1e-9):
        raise ParameterError("a beam's tangent is parallel to the surface normal; the mesh cannot orient its section")
    return n1 / length
