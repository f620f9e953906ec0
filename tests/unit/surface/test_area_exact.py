"""The exact surface's area, ``area_exact`` of the surface protocol (issue 41): what
report.json's ``brep.surfaces[].area_exact`` compares the faces with.

Every expected value is a closed form or an integral written here from a parameterisation
of this file's own (a torus', a frustum's, a surface of revolution's meridian, the Dupin
cyclide's standard one), never the code's output. A sphere zone is not among them: a
sphere is no regular canal surface on a line (its spheres would need |r'| = 1).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from tubecad import CurvatureLineTube, Helix, NaturalAxis, ParametricAxis
from tubecad.surface.canal import CanalSurface
from tubecad.surface.protocol import CurvatureLineSurface

R_MAJOR, R_MINOR = 50.0, 12.0


def torus(span: tuple[float, float], canal: bool) -> CurvatureLineSurface:
    """The tube of radius R_MINOR about the circle of radius R_MAJOR (a helix of slope 0),
    as the tube or as the canal surface of the constant law (its quadrature)."""
    axis = Helix(1.0 / R_MAJOR, 0.0, span)
    return CanalSurface(axis, R_MINOR) if canal else CurvatureLineTube(axis, R_MINOR)


@pytest.mark.parametrize("canal", [False, True], ids=["tube", "canal"])
def test_full_torus_area_is_4_pi2_R_r(canal):
    surface = torus((0.0, 2.0 * math.pi * R_MAJOR), canal)
    assert surface.area_exact == pytest.approx(4.0 * math.pi**2 * R_MAJOR * R_MINOR, rel=1e-13)


@pytest.mark.parametrize("canal", [False, True], ids=["tube", "canal"])
def test_torus_patch_between_two_meridian_planes(canal):
    """Int_0^theta Int_0^2pi r (R + r cos v) dv dphi = 2 pi R r theta."""
    theta = 1.3
    surface = torus((0.0, theta * R_MAJOR), canal)
    assert surface.area_exact == pytest.approx(2.0 * math.pi * R_MAJOR * R_MINOR * theta, rel=1e-13)


def test_cone_frustum_lateral_area():
    """Spheres on a line with r = r0 + m s envelop a cone; between the first and last
    characteristic circles (radius r q at x = s - r m, q = sqrt(1 - m^2)) it is the frustum of
    lateral area pi (R1 + R2) slant. (1e-12: the law "r0 + m s" is held as a Chebyshev series,
    whose r'' is ~1e-12 instead of 0 near the end.)"""
    r0, m, length = 3.0, 0.4, 60.0
    surface = CanalSurface(NaturalAxis("0", "0", (0.0, length)), f"{r0} + {m} * s")
    q = math.sqrt(1.0 - m * m)
    ends = [(s - (r0 + m * s) * m, (r0 + m * s) * q) for s in (0.0, length)]  # (x, radius)
    slant = math.hypot(ends[1][0] - ends[0][0], ends[1][1] - ends[0][1])
    assert surface.area_exact == pytest.approx(math.pi * (ends[0][1] + ends[1][1]) * slant, rel=1e-12)


def test_surface_of_revolution_by_its_meridian():
    """On a straight axis a law r(s) gives a surface of revolution whose meridian is
    (x, rho) = (s - r r', r q) (the characteristic circles); Pappus: A = 2 pi Int rho |P'| ds,
    integrated here by scipy's adaptive quad of the meridian written out."""
    length = 200.0

    def law(s: float) -> tuple[float, float, float]:
        return 10.0 + 3.0 * math.sin(s / 20.0), 0.15 * math.cos(s / 20.0), -0.0075 * math.sin(s / 20.0)

    def density(s: float) -> float:
        r, dr, ddr = law(s)
        q = math.sqrt(1.0 - dr * dr)
        dx, drho = 1.0 - dr * dr - r * ddr, dr * q - r * dr * ddr / q  # d/ds of s - r r' and of r q
        return 2.0 * math.pi * r * q * math.hypot(dx, drho)

    surface = CanalSurface(NaturalAxis("0", "0", (0.0, length)), "10 + 3 * sin(s / 20)")
    exact = quad(density, 0.0, length, epsabs=0.0, epsrel=1e-13, limit=400)[0]
    assert surface.area_exact == pytest.approx(exact, rel=1e-12)


def test_dupin_cyclide_area_by_its_standard_parameterisation():
    """The ring cyclide of spheres on the ellipse x^2/a^2 + y^2/b^2 = 1 with r = mu - (c/a) x
    (c^2 = a^2 - b^2) is, in its standard form (Forsyth; Pratt, CAGD 7 (1990) 221-242),

        X(u, v) = (mu (c - a cos u cos v) + b^2 cos u, b sin u (a - mu cos v),
                   b sin v (c cos u - mu)) / (a - c cos u cos v);

    its whole area is integrated here by the periodic trapezoid rule in u and v (spectrally
    accurate: the integrand is smooth and doubly periodic), X_u and X_v by complex steps."""
    a, b, c, mu = 10.0, 8.0, 6.0, 8.0

    def x(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        d = a - c * np.cos(u) * np.cos(v)
        return np.stack(
            [
                (mu * (c - a * np.cos(u) * np.cos(v)) + b * b * np.cos(u)) / d,
                b * np.sin(u) * (a - mu * np.cos(v)) / d,
                b * np.sin(v) * (c * np.cos(u) - mu) / d,
            ],
            axis=-1,
        )

    n, h = 256, 1e-30
    u, v = np.meshgrid(*(2 * [np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)]), indexing="ij")
    x_u, x_v = x(u + 1j * h, v).imag / h, x(u, v + 1j * h).imag / h
    exact = float(np.linalg.norm(np.cross(x_u, x_v), axis=-1).sum()) * (2.0 * math.pi / n) ** 2

    axis = ParametricAxis(lambda t: np.stack([a * np.cos(t), b * np.sin(t), 0.0 * t], axis=-1), (0.0, 2 * math.pi))
    cyclide = CanalSurface(axis, lambda s: mu - (c / a) * axis.position(s)[..., 0])
    assert cyclide.area_exact == pytest.approx(exact, rel=1e-12)
    # 2 pi r L (what report.json used to state) is 9 % short of it
    assert abs(2.0 * math.pi * mu * axis.length / exact - 1.0) > 0.05


def test_offset_and_restricted_surfaces_have_their_own_area():
    """A wall's inner surface is the offset r + d (the frustum of r0 + d + m s: r0 shifted),
    and a piece of the span has the area of that piece (the torus patch's)."""
    r0, m, length, d = 3.0, 0.4, 60.0, -1.5
    axis = NaturalAxis("0", "0", (0.0, length))
    inner = CanalSurface(axis, f"{r0} + {m} * s").offset(d)
    assert inner.area_exact == pytest.approx(CanalSurface(axis, f"{r0 + d} + {m} * s").area_exact, rel=1e-13)
    whole = torus((0.0, 2.0 * math.pi * R_MAJOR), canal=True)
    piece = whole.restricted((0.0, 0.5 * math.pi * R_MAJOR))
    assert piece.area_exact == pytest.approx(math.pi**2 * R_MAJOR * R_MINOR, rel=1e-13)
