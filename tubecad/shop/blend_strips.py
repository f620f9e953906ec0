"""A crotch blend's shop data (issue 43): its surface developed in strips, and its toe lines.

The blend (:class:`~tubecad.junctions.blend.RollingBall`) is the tube of radius rb about the
ball's centre curve: its rings, the ball's characteristic circles, and its stringers are its
lines of curvature. Between two of its rings s_i < s_(i+1) (the rings the solid names
``blend_ring_..``) the blend is a strip of that tube bounded across by the two contact curves
(the weld's toes); each strip is developed as a panel of the tube
(:func:`tubecad.shop.panel_development.develop_panel`: its middle stringer and its rings kept
isometric) over the stringers that hold its piece of the blend (every other ring of the
solid's bounds a strip), the toes drawn on it as
marking lines (cut along them). A strip develops where its largest strain is within the
fabrication's ``max_strain``; a blend of a small radius on a tight saddle does not (its
Gaussian curvature K ~ 1 / (rb rho), rho the centre curve's radius of curvature, and a
strip's strain ~ K d^2 / 2 at d from its middle stringer): it is then formed (pressed, or a
forged fitting's crotch) and its strips are the forming's gauges.

The toes in the shop's other drawings are the saddle of the walls offset by rb (the ball's
centre curve) read on each wall: its (u_B, s_B) on the branch's cutting template, its
(u_A, s_A) on the main's (:mod:`tubecad.design.junction_shop`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tubecad.junctions.blend import BLEND_RINGS, RollingBall
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.shop.panel_development import PanelDevelopment, develop_panel

#: the rings of a strip on which its toes are traced
TOE_SAMPLES = 65
#: the strips' rings: every other ring of the solid's blend (BLEND_RINGS)
STRIP_RINGS = (BLEND_RINGS + 1) // 2
#: the strips' strain grid (nodes across, along): a strip is short and its strain smooth
STRIP_GRID = (17, 17)


@dataclass(frozen=True)
class BlendStrip:
    """One strip of a blend: its ``development`` and the two toes on it (``toes``: (name,
    (n, 2) developed points), ``toe_main`` and ``toe_branch``)."""

    development: PanelDevelopment
    toes: list[tuple[str, np.ndarray]]


def blend_strips(ball: RollingBall, name: str, rings: int = STRIP_RINGS) -> list[BlendStrip]:
    """The ``ball``'s blend developed in the strips between ``rings`` rings of its tube, evenly
    round its centre curve (module docstring); strip i is named ``{name}_strip_{i:02d}``.

    Args:
        ball: the blend.
        name: the strips' names' stem (``branch_0_blend``).
        rings: the rings bounding the strips (STRIP_RINGS: every other of the solid's).

    Returns:
        The strips, in the order of the centre curve.
    """
    surface = ball.surface
    s0, s1 = surface.span
    edges = np.linspace(s0, s1, rings)
    strips: list[BlendStrip] = []
    for i, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
        at = np.linspace(lo, hi, TOE_SAMPLES)
        toe_a, toe_b = _toes(ball, at)
        low, high = np.degrees(min(toe_a.min(), toe_b.min())), np.degrees(max(toe_a.max(), toe_b.max()))
        development = develop_panel(surface, (float(lo), float(hi)), (low, high), f"{name}_strip_{i:02d}", STRIP_GRID)
        toes = [
            ("toe_main", development.map(np.degrees(toe_a), at)),
            ("toe_branch", development.map(np.degrees(toe_b), at)),
        ]
        strips.append(BlendStrip(development, toes))
    return strips


def _toes(ball: RollingBall, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The stringer angles u on the blend's tube of the toes on its rings ``s``: the ball
    centred at the ring's centre C touches the main at C - rb n_A and the branch at C - rb n_B
    (the walls' normals at C's feet on their offsets, which keep their parameters), and the
    short arc from the first to the second is the blend's (u unwrapped along ``s``)."""
    surface, rb = ball.surface, ball.radius
    centre = surface.axis.position(s)
    contacts = []
    for wall in (ball.main, ball.branch):
        foot = surface_coordinates(wall.offset(rb), centre)
        contacts.append(surface_coordinates(surface, centre - rb * wall.normal(foot.u, foot.s)).u)
    u_main = np.unwrap(contacts[0])
    return u_main, u_main + np.angle(np.exp(1j * (contacts[1] - contacts[0])))
