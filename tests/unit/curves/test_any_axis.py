"""Any axis (issue 11, docs/MATH.md section 7): the Axis protocol on every kind, checked
against closed forms (slope curves, a helix) and against its own definition by finite
differences; tubes on them keep F = M = 0, and their walls are valid solids."""

import math

import numpy as np
import pytest

from tubecad import CurvatureLineTube, Helix, LogSpiral, ParameterError
from tubecad.curves import Axis
from tubecad.curves.natural import NaturalAxis
from tubecad.curves.parametric import ParametricAxis, expression_curve


def central_difference(f, s, h):
    """Fourth-order central difference of f at s."""
    return (-f(s + 2 * h) + 8 * f(s + h) - 8 * f(s - h) + f(s - 2 * h)) / (12 * h)


def natural_twin(slope) -> NaturalAxis:
    """The slope curve as natural equations (tau = k tan b, Lancret), from its start frame."""
    s0 = slope.span[0]
    a = slope.evaluate(np.array([s0]))
    tan_b = math.tan(slope.beta)
    return NaturalAxis(
        lambda s: slope.curvature(s),
        lambda s: slope.curvature(s) * tan_b,
        slope.span,
        origin=a.position[0],
        tangent=a.t[0],
        normal=a.n[0],
    )


def helix_curve(R: float, h: float) -> tuple[ParametricAxis, float]:
    """x = (R cos t, R sin t, h t): arc length s = t sqrt(R^2 + h^2) exactly."""
    return ParametricAxis(expression_curve(f"{R} * cos(t)", f"{R} * sin(t)", f"{h} * t"), (0.0, 6.0)), math.hypot(R, h)


AXES = {
    "log_spiral": lambda: LogSpiral(10.0, 10.0, (200.0, 1200.0)),
    "natural": lambda: NaturalAxis("0.01 + 0.005 * sin(s / 50)", "0.004 * cos(s / 80)", (0.0, 600.0)),
    "parametric_helix": lambda: helix_curve(40.0, 7.0)[0],
    "parametric_inflection": lambda: ParametricAxis(expression_curve("100 * t", "100 * t**3", "10 * t"), (-1.0, 1.0)),
    "parametric_straight_then_bent": lambda: ParametricAxis(  # a line, then a C2 bend: breaks at the join
        lambda t: np.stack([t, np.where(t > 0, t**4, 0.0), 0 * t], axis=-1), (-1.0, 1.0), breaks=[-1.0, 0.0, 1.0]
    ),
}


@pytest.mark.parametrize("name", sorted(AXES))
def test_the_frame_solves_the_bishop_equations(name):
    """c' = t, t' = k1 r1 + k2 r2, r1' = -k1 t, r2' = -k2 t, (t, r1, r2) orthonormal: checked
    by finite differences of what the axis returns, not by how it computed it."""
    axis: Axis = AXES[name]()
    s0, s1 = axis.span
    h = 1e-4 * (s1 - s0)
    s = np.linspace(s0 + 4 * h, s1 - 4 * h, 401)
    a = axis.at(s)
    frame = np.stack([a.t, a.r1, a.r2], axis=1)
    assert np.abs(frame @ frame.transpose(0, 2, 1) - np.eye(3)).max() < 1e-12
    assert np.abs(central_difference(axis.position, s, h) - a.t).max() < 1e-9
    k = np.abs(a.curvature_vector).max() + 1.0 / axis.length
    dt = central_difference(lambda x: axis.rotation_minimising_frame(x)[0], s, h)
    dr1 = central_difference(lambda x: axis.rotation_minimising_frame(x)[1], s, h)
    dr2 = central_difference(lambda x: axis.rotation_minimising_frame(x)[2], s, h)
    assert np.abs(dt - a.curvature_vector).max() < 1e-7 * k
    assert np.abs(dr1 + a.k1[:, None] * a.t).max() < 1e-7 * k
    assert np.abs(dr2 + a.k2[:, None] * a.t).max() < 1e-7 * k
    dk1, dk2 = axis.normal_development_derivative(s)
    fd1, fd2 = (central_difference(lambda x, i=i: axis.normal_development(x)[i], s, h) for i in (0, 1))
    scale = np.abs(fd1).max() + np.abs(fd2).max() + k / axis.length
    assert np.abs(dk1 - fd1).max() < 1e-6 * scale and np.abs(dk2 - fd2).max() < 1e-6 * scale


@pytest.mark.parametrize("name", sorted(AXES))
def test_rings_and_stringers_are_lines_of_curvature_on_every_axis(name):
    """F = M = 0 to 1e-10 on the exact grid, E = rho^2, L = -rho (docs/MATH.md section 7)."""
    axis = AXES[name]()
    k_max = np.abs(axis.curvature(np.linspace(*axis.span, 2001))).max()
    rho = 0.5 / max(k_max, 1.0 / axis.length)
    tube = CurvatureLineTube(axis, rho, allow_irregular=True)
    u = np.linspace(0.0, 2 * math.pi, 37)[:, None]
    s = np.linspace(*axis.span, 301)[None, :]
    f = tube.fundamental_forms(u, s)
    assert np.abs(f.F).max() < 1e-10 * rho and np.abs(f.M).max() < 1e-10
    assert np.abs(f.E - rho**2).max() < 1e-10 * rho**2 and np.abs(f.L + rho).max() < 1e-10 * rho


@pytest.mark.parametrize(
    "slope",
    [LogSpiral(10.0, 10.0, (200.0, 1200.0)), Helix(0.02, 30.0, (0.0, 1000.0)), Helix(0.05, 0.0, (0.0, 125.0))],
    ids=["log_spiral", "helix", "circle"],
)
def test_natural_equations_give_the_closed_form_tube(slope):
    """The slope curve given as k(s), tau = k tan b: the same axis and the same tube to 1e-10
    relative, up to the constant turn w(s0) of the start frame."""
    natural = natural_twin(slope)
    s = np.linspace(*slope.span, 4001)
    scale = np.abs(slope.position(s)).max() + slope.length
    assert np.abs(natural.position(s) - slope.position(s)).max() < 1e-10 * scale
    w0 = float(slope.twist(np.array([slope.span[0]]))[0])
    rho = 0.5 / np.abs(slope.curvature(s)).max()
    exact = CurvatureLineTube(slope, rho).grid(np.linspace(0, 2 * math.pi, 25) + w0, s)
    ours = CurvatureLineTube(natural, rho).grid(np.linspace(0, 2 * math.pi, 25), s)
    assert np.abs(ours - exact).max() < 1e-10 * scale


def test_a_parametric_helix_is_the_helix():
    """x = (R cos t, R sin t, h t): s = t sqrt(R^2 + h^2), k = R / (R^2 + h^2), and the RMF
    turns against the Frenet normal at the rate tau = h / (R^2 + h^2)."""
    R, h = 40.0, 7.0
    axis, speed = helix_curve(R, h)
    assert axis.length == pytest.approx(6.0 * speed, rel=1e-14)
    s = np.linspace(*axis.span, 2001)
    t = s / speed
    exact = np.stack([R * np.cos(t), R * np.sin(t), h * t], axis=1)
    assert np.abs(axis.position(s) - exact).max() < 1e-11 * R
    k1, k2 = axis.normal_development(s)
    assert np.abs(np.hypot(k1, k2) - R / speed**2).max() < 5e-11 * R / speed**2
    w = np.unwrap(np.arctan2(k2, k1))  # the Frenet normal's angle in (r1, r2): w0 + Int tau ds
    assert np.abs((w - w[0]) - h / speed**2 * s).max() < 1e-10 * (1 + h / speed**2 * s[-1])


def test_the_frame_passes_an_inflection_without_a_jump():
    """At x = (t, t^3, 0.1 t), t = 0, the Frenet normal flips; the RMF does not."""
    axis = AXES["parametric_inflection"]()
    s = np.linspace(*axis.span, 4001)
    _, r1, r2 = axis.rotation_minimising_frame(s)
    step = np.diff(s).max()
    k_max = np.abs(axis.curvature(s)).max()
    assert np.linalg.norm(np.diff(r1, axis=0), axis=1).max() <= 1.01 * k_max * step
    k = axis.curvature(s)
    assert k.min() < 1e-6 * k_max  # the inflection is sampled


@pytest.mark.parametrize(
    "make, says",
    [
        (lambda: ParametricAxis(expression_curve("t**2", "t**3", "0"), (-1.0, 1.0)), "degenerate: its speed"),
        (lambda: ParametricAxis(expression_curve("t", "log(t)", "0"), (-1.0, 1.0)), "not finite"),
        (lambda: NaturalAxis("1 / s", "0", (-1.0, 1.0)), r"k\(s\) is not finite at s = 0"),
        (
            lambda: NaturalAxis("0.1", "0", (0.0, 1.0), tangent=[1, 0, 0], normal=[2, 0, 0]),
            "normal must not be parallel",
        ),
        (lambda: NaturalAxis("0.1", "0", (0.0, 1.0), tangent=[0, 0, 0]), "tangent must not be the zero vector"),
    ],
)
def test_bad_axes_are_refused_naming_what_is_wrong(make, says):
    with pytest.raises(ParameterError, match=says):
        make()


@pytest.mark.slow
@pytest.mark.parametrize("name", ["natural", "parametric_inflection"])
def test_walls_on_new_axes_are_valid_and_within_tolerance(name):
    """The whole pipeline on the axis: a wall solid, valid, no analyzer finding, its faces
    within the fit tolerance of the exact tubes and orthogonal to 1e-9 (dense sampling)."""
    from tubecad.brep import NetLayout, build_wall_solid
    from tubecad.brep.measure import measure_tube_faces
    from tubecad.brep.properties import analyzer_findings, volume

    axis = AXES[name]()
    k_max = np.abs(axis.curvature(np.linspace(*axis.span, 2001))).max()
    rho = 0.3 / k_max
    tube = CurvatureLineTube(axis, rho)
    build = build_wall_solid(tube, 0.1 * rho, "centered", NetLayout.equal(tube, 7, 6))
    assert (
        build.shape.is_valid
        and analyzer_findings(build.shape, modes=("SmallEdgeMode", "ContinuityMode", "CurveOnSurfaceMode")) == {}
    )
    measured = measure_tube_faces(build.shape, axis, build.radii, samples=6000)
    assert measured.faces == 2 * 6 * 6
    assert measured.max_deviation < 1e-8 and measured.max_orthogonality < 1e-9
    assert volume(build.shape) == pytest.approx(
        math.pi * (build.radii[0] ** 2 - build.radii[1] ** 2) * axis.length, rel=1e-9
    )


def test_an_axis_starting_at_a_near_inflection_gets_a_start_normal():
    """x = (t, 1e-7 t^2 + 1e-3 t^3, 0): at t = 0 the curvature is 2e-7, its Frenet normal
    (0, 1, 0) up to round-off. The start normal once failed the parallel check against an
    unnormalised tangent derivative and the axis was refused (random-spec run, issue 24)."""
    axis = ParametricAxis(lambda t: np.stack([t, 1e-7 * t**2 + 1e-3 * t**3, 0 * t], axis=-1), (0.0, 10.0))
    t, r1, r2 = (v[0] for v in axis.rotation_minimising_frame(np.array([axis.span[0]])))
    assert np.allclose(t, [1.0, 0.0, 0.0], atol=1e-12)
    assert abs(np.dot(t, r1)) < 1e-12 and abs(np.dot(r1, r2)) < 1e-12
    assert abs(np.dot(r1, [0.0, 1.0, 0.0])) > 1 - 1e-9  # the plane's normal: r2 is +-z


def test_a_long_closed_curve_far_out_resolves_its_frame():
    """Random-spec case 31: a closed sum of sines, ~1e6 across with k L ~ 1e3. Its frame in s
    once had to be resolved to 1e-15 absolute, below what 2048 panels of doubles can hold
    there, and the axis was refused; the floor is now 4 eps L k_max (round-off of the
    frame's integral). The frame must come out orthonormal and closing on itself."""
    x = [(306795.316321, 3.0, 2.48680202677), (113443.624595, 2.0, 4.96514152053), (107667.696276, 2.0, 4.79474462484)]
    y = [(539048.255848, 1.0, 2.06944083329), (167174.43602, 1.0, 1.61344030209), (82991.7960451, 1.0, 4.50498537396)]
    z = [(492206.849562, 1.0, 1.86110375891), (291136.95743, 3.0, 2.43071948788), (53482.3679879, 3.0, 5.42671168095)]

    def curve(t):
        return np.stack([sum(a * np.sin(f * t + p) for a, f, p in c) for c in (x, y, z)], axis=-1)

    axis = ParametricAxis(curve, (0.0, 2 * math.pi), closed=True)
    s = np.linspace(*axis.span, 2001)
    t, r1, r2 = axis.rotation_minimising_frame(s)
    frame = np.stack([t, r1, r2], axis=-2)
    assert np.abs(frame @ frame.transpose(0, 2, 1) - np.eye(3)).max() < 1e-12
    assert np.linalg.norm(axis.position(s[-1:]) - axis.position(s[:1])) < 1e-9 * axis.length
    assert np.linalg.norm(t[-1] - t[0]) < 1e-10
