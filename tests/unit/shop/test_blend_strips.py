"""A crotch blend's developed strips (issue 43), against the perpendicular tee's closed form.

The main y^2 + z^2 = R^2 (along x) and the branch x^2 + y^2 = r^2 (along z): the ball of radius
rb rolled between them has its centre at C = ((r + rb) cos phi, (r + rb) sin phi, z) on both
offset cylinders, touches the main along -(0, y_C, z_C) / (R + rb) and the branch along
-(cos phi, sin phi, 0), so the blend's ring there is an arc of rb times the angle between them,
arccos((r + rb) sin^2 phi / (R + rb)). On the blend's tube (constant radius) each ring develops
isometrically to a straight segment: on every strip, the two toes' ends on a bounding ring lie
that arc's length apart, in a straight line with the ring's side of the outline."""

from __future__ import annotations

import math

import numpy as np

from tubecad import NaturalAxis, tube_or_canal
from tubecad.junctions.blend import rolling_ball
from tubecad.junctions.coordinates import surface_coordinates
from tubecad.shop.blend_strips import blend_strips

R, r, RB = 50.0, 20.0, 5.0


def line(origin, tangent, normal, length, radius):
    return tube_or_canal(NaturalAxis("0", "0", (0.0, length), origin=origin, tangent=tangent, normal=normal), radius)


MAIN = line((-100.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), 200.0, R)
BRANCH = line((0.0, 0.0, 0.0), (0, 0, 1), (1, 0, 0), 120.0, r)


def test_each_strips_rings_carry_the_balls_arc_between_the_toes():
    ball = rolling_ball(MAIN, BRANCH, RB, 1e-9)
    strips = blend_strips(ball, "blend", rings=5)
    assert [s.development.name for s in strips] == [f"blend_strip_{i:02d}" for i in range(4)]
    for strip in strips:
        development = strip.development
        (_, toe_main), (_, toe_branch) = strip.toes
        for end, s in ((0, development.s_range[0]), (-1, development.s_range[1])):
            centre = ball.surface.axis.position(np.array([s]))[0]
            phi = math.atan2(centre[1], centre[0])
            # the centre is the closed form's at its own phi (on both offset cylinders)
            assert abs(math.hypot(centre[1], centre[2]) - (R + RB)) < 1e-13 * R  # measured 4e-15 R
            assert abs(math.hypot(centre[0], centre[1]) - (r + RB)) < 1e-13 * R
            arc = RB * math.acos((r + RB) * math.sin(phi) ** 2 / (R + RB))
            chord = np.linalg.norm(toe_main[end] - toe_branch[end])
            assert abs(chord - arc) < 1e-13 * R  # measured 1e-15 R
            ring = development.ring_line(s, 33)  # the developed ring: straight, the toes' ends on it
            direction = (ring[-1] - ring[0]) / np.linalg.norm(ring[-1] - ring[0])
            for point in (*ring, toe_main[end], toe_branch[end]):
                off = point - ring[0]
                assert abs(off[0] * direction[1] - off[1] * direction[0]) < 1e-13 * R  # measured 1e-16 R
        # doubly curved (Gauss: K != 0, no development without strain): measured 8.3 %, above
        # the default 1 % a shop develops within
        assert development.max_strain > 0.01


def test_the_strips_cover_the_centre_curve_once():
    ball = rolling_ball(MAIN, BRANCH, RB, 1e-9)
    strips = blend_strips(ball, "blend", rings=5)
    spans = [s.development.s_range for s in strips]
    assert spans[0][0] == ball.surface.span[0] and spans[-1][1] == ball.surface.span[1]
    assert all(a[1] == b[0] for a, b in zip(spans, spans[1:]))
    on_main = surface_coordinates(ball.surface, ball.contact_points(np.linspace(0, 2 * math.pi, 9))[1])
    assert np.abs(on_main.gap).max() < 1e-9 * R  # the toes lie on the blend's tube
