"""The opening a branch's bore cuts in a main tube whose radius varies (a nozzle on a conical
head), developed as a panel of the main's surface round it.

A tube of constant radius develops to a strip, (R u, s - s_0), and its opening is drawn there
(:func:`tubecad.shop.branch_template.hole_template`). A canal surface does not: its rings
develop to circular arcs and a cone to a sector. So the opening is drawn on the development
of the panel of the main's surface that bounds it, :func:`tubecad.shop.panel_development.develop_panel`:
the rings s_a < s_b and the stringers u_a < u_b round the saddle's extent with a ``margin``
every way (clipped to the main's span; round the axis the margin is measured at the smallest
ring radius r q, q = sqrt(1 - r'^2), of the panel), the middle stringer and every ring kept
isometric. A cone's development is then exact (strain 0 to round-off: its Gaussian curvature
is 0); a curved or non-linear radius law gives the strain that development reports, its
largest value over the panel's grid being ``max_strain``. The bore's saddle (u_A, s_A) is
mapped onto the development by the construction itself (no interpolation).

The drawing (1:1, :func:`save_hole_dxf`): the opening as one closed polyline on layer
``saddle`` (as on the strip's template), the panel's outline (two rings and two stringers of
the main) on ``outline``, a mark along each of the main's stringers that crosses the panel,
from its ring s_a, with its name on ``girth_marks``, and the panel's name, rings, stringers
and largest strain on ``text``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.dxf import Drawing
from tubecad.core.errors import ParameterError
from tubecad.junctions.saddle import SaddleCurve
from tubecad.shop.panel_development import PanelDevelopment, develop_panel
from tubecad.surface.protocol import CurvatureLineSurface

#: the marks' length along their stringer, as a share of the panel's developed height
MARK_SHARE = 0.05
#: the drawing's layers, name -> DXF colour index
HOLE_LAYERS = {"saddle": 1, "outline": 7, "girth_marks": 3, "text": 5}


def hole_bounds(
    main: CurvatureLineSurface, saddle: SaddleCurve, margin: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """((s_a, s_b), (u_a, u_b) in degrees): the rings and stringers ``margin`` beyond the
    saddle's extent on ``main`` (see the module), the rings clipped to the main's span and
    the stringers to one turn."""
    if isinstance(margin, bool) or not (isinstance(margin, (int, float)) and margin > 0 and math.isfinite(margin)):
        raise ParameterError(f"margin must be a finite length > 0, got {margin!r:.40}", key="margin")
    s0, s1 = main.span
    (s_lo, s_hi), (u_lo, u_hi) = saddle.extent(saddle.main_s), saddle.extent(saddle.main_u)
    s_a, s_b = max(s_lo - margin, s0), min(s_hi + margin, s1)
    inside = np.linspace(s_a, s_b, 257)
    ring = float((main.radius_law.r(inside) * np.sqrt(1.0 - main.radius_law.dr(inside) ** 2)).min())
    around = min(margin / ring, math.pi - 0.5 * (u_hi - u_lo))  # at most one turn in all
    if not around > 0:
        raise ParameterError("the opening reaches all round the main tube: it has no panel", key="margin")
    return (s_a, s_b), (math.degrees(u_lo - around), math.degrees(u_hi + around))


def hole_development(
    main: CurvatureLineSurface, saddle: SaddleCurve, margin: float, name: str = "hole"
) -> tuple[PanelDevelopment, np.ndarray]:
    """The opening ``saddle`` cuts in ``main`` developed on the panel of ``main`` round it.

    The panel is bounded by two rings and two stringers of ``main``, ``margin`` beyond the
    saddle's extent every way (:func:`hole_bounds`), and developed as
    :func:`tubecad.shop.panel_development.develop_panel` does (docs/MATH.md section 9): its
    middle stringer develops isometrically to a plane curve of the stringer's geodesic
    curvature and every ring isometrically from it, square to it, so a surface of zero
    Gaussian curvature develops without strain: a cone unrolls exactly, a point at slant
    distance rho from the apex and angle theta round the axis going to the polar point
    (rho, theta sin a), a the half-angle. Where the surface is doubly curved the
    development's strain is measured, not zero (its ``max_strain``). Any main surface works,
    a tube of constant radius too (there the strip of :func:`tubecad.shop.branch_template.hole_template`
    is the simpler drawing).

    Args:
        main: the main tube's surface the opening is cut in (the inner wall surface for the
            bore's saddle), a tube or a canal surface.
        saddle: the saddle on ``main`` (its ``main_u``, ``main_s``), closed (the last sample
            the first again), e.g. the branch bore's saddle on the main's inner surface.
        margin: how far beyond the saddle's extent the panel reaches along the axis and round
            it (a length > 0; clipped to the main's span).
        name: the development's name (no path separators), e.g. ``branch_0_hole``.

    Returns:
        (development, line): the panel's :class:`tubecad.shop.panel_development.PanelDevelopment`
        and the saddle's developed points (n, 2), one per saddle sample, closed as the saddle
        is.

    Raises:
        ParameterError: ``margin`` not a length > 0 (key ``margin``), or an opening round the
            whole main tube.
    """
    s_range, angles = hole_bounds(main, saddle, margin)
    development = develop_panel(main, s_range, angles, name)
    line = development.map(np.degrees(saddle.main_u), saddle.main_s)
    return development, line


def save_hole_dxf(
    development: PanelDevelopment,
    line: np.ndarray,
    path: str | Path,
    unit: str = "mm",
    stringers: Mapping[str, float] | None = None,
) -> Path:
    """The developed opening at 1:1 as a DXF drawing, written atomically: ``line`` (closed:
    drawn once round) on layer ``saddle``, ``development``'s outline on ``outline``, a mark
    from the ring s_a a twentieth of the way up each of ``stringers`` ({name: angle in degrees}, an angle taken
    modulo 360 into the panel's angles) that crosses the panel on ``girth_marks``, and the
    panel's description on ``text``."""
    points = np.asarray(line, dtype=float)
    outline = development.outline()
    size = float(np.ptp(outline, axis=0).max())
    closed = bool(np.allclose(points[0], points[-1], rtol=0, atol=1e-9 * size))
    drawing = Drawing(unit, HOLE_LAYERS)
    drawing.polyline(points[:-1] if closed else points, "saddle", closed=closed)
    drawing.polyline(outline, "outline", closed=True)
    (u_a, u_b), (s_a, s_b) = development.angle_range, development.s_range
    s_mark = s_a + MARK_SHARE * (s_b - s_a)
    height = float(np.linalg.norm(development.map(u_a, s_mark) - development.map(u_a, s_a)))
    for mark, angle in (stringers or {}).items():
        u = u_a + (float(angle) - u_a) % 360.0
        if u <= u_b:
            top = development.map(u, s_mark)
            drawing.line(development.map(u, s_a), top, "girth_marks")
            drawing.text(mark, top, height / 2, "girth_marks")
    low = outline.min(axis=0)
    note = (
        f"{development.name}: rings s = {s_a:.6g} .. {s_b:.6g}, stringers u = {u_a:.6g} .. {u_b:.6g} deg, "
        f"max strain {development.max_strain:.3e}"
    )
    drawing.text(note, (float(low[0]), float(low[1]) - 2.0 * height), 0.6 * height, "text")
    return drawing.save(path)


@dataclass(frozen=True)
class HolePanel:
    """A developed opening: the panel's ``development``, the saddle's developed ``line`` on
    it (closed) and the main's stringers to mark, ``stringers`` {name: angle in degrees}."""

    development: PanelDevelopment
    line: np.ndarray
    stringers: Mapping[str, float] = field(default_factory=dict)

    def save_dxf(self, path: str | Path, unit: str = "mm") -> Path:
        """The drawing of :func:`save_hole_dxf`."""
        return save_hole_dxf(self.development, self.line, path, unit, self.stringers)

    def info(self) -> dict[str, Any]:
        """The index's entry: ``developed`` "panel", the developed outline's ``width`` and
        ``height`` (its bounding box: the template's sheet), the panel's rings ``s_range``
        and stringers ``angles_deg`` on the main and the development's largest ``strain``."""
        width, height = np.ptp(self.development.outline(), axis=0)
        return {
            "developed": "panel",
            "width": float(width),
            "height": float(height),
            "s_range": list(self.development.s_range),
            "angles_deg": list(self.development.angle_range),
            "strain": self.development.max_strain,
        }
