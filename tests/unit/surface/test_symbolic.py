"""Symbolic proof (sympy) of docs/MATH.md section 3 for the general slope-curve tube.

psi(s) is an arbitrary function; the axis is only known through c'(s) = t(psi), which
is what makes s its arc length. The claims: E = rho^2, F = 0, G = (1 - rho k cos phi)^2,
L = -rho, M = 0, N = k cos phi (1 - rho k cos phi) with k = psi' cos b and
phi = u - psi sin b; and dropping the twist compensation (v = u) breaks F = 0.
"""

import pytest
import sympy as sp

u, s, rho, b = sp.symbols("u s rho beta", real=True)
psi = sp.Function("psi", real=True)(s)
X0, Y0, Z0 = (sp.Function(n, real=True)(s) for n in ("x0", "y0", "z0"))

T = sp.Matrix([sp.cos(b) * sp.cos(psi), sp.cos(b) * sp.sin(psi), sp.sin(b)])
NRM = sp.Matrix([-sp.sin(psi), sp.cos(psi), 0])
BN = sp.Matrix([-sp.sin(b) * sp.cos(psi), -sp.sin(b) * sp.sin(psi), sp.cos(b)])
K = sp.diff(psi, s) * sp.cos(b)  # psi' = k / cos b (paper eq. 8)


def axis_derivatives(expr):
    """Replace c', c'' by t, t' (the axis is parameterised by arc length)."""
    c1 = {sp.Derivative(f, s): T[i] for i, f in enumerate((X0, Y0, Z0))}
    c2 = {sp.Derivative(f, (s, 2)): sp.diff(T[i], s) for i, f in enumerate((X0, Y0, Z0))}
    return expr.subs(c2).subs(c1)


def forms(phi):
    S = sp.Matrix([X0, Y0, Z0]) + rho * (sp.cos(phi) * NRM + sp.sin(phi) * BN)
    Su, Ss = S.diff(u), axis_derivatives(S.diff(s))
    Suu, Sus, Sss = S.diff(u, 2), axis_derivatives(S.diff(u, s)), axis_derivatives(S.diff(s, 2))
    normal = sp.cos(phi) * NRM + sp.sin(phi) * BN  # outward unit normal of the tube
    simplify = lambda e: sp.simplify(sp.trigsimp(sp.expand(e)))
    return {
        "E": simplify(Su.dot(Su)),
        "F": simplify(Su.dot(Ss)),
        "G": simplify(Ss.dot(Ss)),
        "L": simplify(Suu.dot(normal)),
        "M": simplify(Sus.dot(normal)),
        "N": simplify(Sss.dot(normal)),
        "normal_is_normal": (simplify(normal.dot(Su)), simplify(normal.dot(Ss))),
    }


@pytest.mark.slow
def test_curvature_line_parameterisation_general_slope_curve():
    phi = u - psi * sp.sin(b)
    f = forms(phi)
    assert f["normal_is_normal"] == (0, 0)
    assert sp.simplify(f["E"] - rho**2) == 0
    assert f["F"] == 0
    assert sp.simplify(f["G"] - (1 - rho * K * sp.cos(phi)) ** 2) == 0
    assert sp.simplify(f["L"] + rho) == 0
    assert f["M"] == 0
    assert sp.simplify(f["N"] - K * sp.cos(phi) * (1 - rho * K * sp.cos(phi))) == 0


@pytest.mark.slow
def test_frenet_parameterisation_is_not_orthogonal():
    """Without phi = u - psi sin b the net is not orthogonal: F = rho^2 * torsion."""
    f = forms(u)
    assert sp.simplify(f["F"] - rho**2 * K * sp.tan(b)) == 0


def test_rotation_minimising_tube_on_any_axis():
    """docs/MATH.md section 7, for any C2 axis: vectors are written in the moving basis
    (t, r1, r2), differentiated with c' = t, t' = k1 r1 + k2 r2, r1' = -k1 t, r2' = -k2 t
    (k1, k2 arbitrary functions). Then S = c + rho (cos u r1 + sin u r2) has E = rho^2,
    F = 0, G = (1 - rho (k1 cos u + k2 sin u))^2, L = -rho, M = 0."""
    k1, k2 = (sp.Function(n, real=True)(s) for n in ("k1", "k2"))

    def d_ds(v):  # v = (a, b, c) means a t + b r1 + c r2
        a, bb, c = v
        return sp.Matrix([sp.diff(a, s) - k1 * bb - k2 * c, sp.diff(bb, s) + k1 * a, sp.diff(c, s) + k2 * a])

    radial = sp.Matrix([0, sp.cos(u), sp.sin(u)])
    Su = rho * radial.diff(u)  # c does not depend on u
    Ss = sp.Matrix([1, 0, 0]) + rho * d_ds(radial)
    Suu, Sus, Sss = rho * radial.diff(u, 2), d_ds(Su), d_ds(Ss)
    simplify = lambda e: sp.simplify(sp.trigsimp(sp.expand(e)))
    assert simplify(Su.dot(Su) - rho**2) == 0
    assert simplify(Su.dot(Ss)) == 0
    assert simplify(Ss.dot(Ss) - (1 - rho * (k1 * sp.cos(u) + k2 * sp.sin(u))) ** 2) == 0
    assert simplify(radial.dot(Su)) == 0 and simplify(radial.dot(Ss)) == 0  # the radial unit vector is the normal
    assert simplify(Suu.dot(radial) + rho) == 0
    assert simplify(Sus.dot(radial)) == 0
    assert (
        simplify(Sss.dot(radial) - (k1 * sp.cos(u) + k2 * sp.sin(u)) * (1 - rho * (k1 * sp.cos(u) + k2 * sp.sin(u))))
        == 0
    )
