"""The one surface every stage after the surface takes (docs/MATH.md sections 2, 7, 8).

A surface referred to its lines of curvature over an axis c(s) with the rotation-minimising
frame (t, r1, r2) and a radius law r(s), |r'| < 1, q = sqrt(1 - r'^2), e = cos chi r1 + sin chi r2:

    X(u, s) = c + r ( -r' t + q e ),   chi = chi(u, s) the stringer's angle, chi(u, s0) = u

The rings s = const are the characteristic circles (centre c - r r' t, radius r q, plane
normal t) and the stringers u = const their orthogonal trajectories; on them the half-angle
vector (sin(chi/2), cos(chi/2)) moves by the 2 x 2 fundamental matrix Mb(s) (a Moebius map
of the circle). The tube is the case r = rho constant: r' = 0, q = 1, Mb = I, chi = u, so
X = c + rho e (paper eq. 7) and every member has a closed form; ``constant_radius`` says
that the tube's fast path applies (the 9-component frame fit instead of the canal's 21,
the tube's grid and step rules), ``fast_path()`` gives the object that takes it. Code that
only one kind can run (a tube's closed-form report, a canal stringer's Newton steps on the
exact surface) asks :meth:`~CurvatureLineSurface.dispatch` for it: the surface calls back
the function for its own kind (double dispatch), so no one downcasts it.

:class:`~tubecad.surface.tube.CurvatureLineTube` and :class:`~tubecad.surface.canal.CanalSurface`
both satisfy :class:`CurvatureLineSurface`; code after the surface asks these members, never
the concrete class (tests/design/test_architecture.py checks it).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol, TypeGuard, TypeVar, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from tubecad.curves.axis import Axis
from tubecad.curves.radius_law import RadiusLaw
from tubecad.surface.forms import FundamentalForms, SurfaceDerivatives

if TYPE_CHECKING:  # the two kinds, named in :meth:`CurvatureLineSurface.dispatch` only
    from tubecad.surface.canal import CanalSurface
    from tubecad.surface.tube import CurvatureLineTube

FloatArray = np.ndarray
T = TypeVar("T")


@runtime_checkable
class CurvatureLineSurface(Protocol):
    """A canal surface (the tube its r = const case) in curvature-line coordinates (u, s):
    u (period 2 pi) names the stringer by its angle chi from r1 at the span's start, s is
    the axis arc length. Implemented by CurvatureLineTube and CanalSurface."""

    #: the axis c(s), its rotation-minimising frame and normal development (k1, k2)
    axis: Axis
    #: what was measured about the surface's regularity (a RegularityReport or CanalRegularity)
    regularity: Any

    @property
    def span(self) -> tuple[float, float]:
        """(s0, s1), the axis' span."""
        ...

    @property
    def length(self) -> float:
        """L = s1 - s0, the axis length over the span."""
        ...

    @property
    def area_exact(self) -> float:
        """The exact surface's area over the span, A = Int Int sqrt(E G - F^2) du ds (F = 0):
        a tube's 2 pi rho L (Pappus-Guldin, docs/MATH.md section 4), a canal surface's by
        quadrature of its exact derivatives (section 8)."""
        ...

    @property
    def radius_law(self) -> RadiusLaw:
        """r(s) with r', r'', r''' (a tube: the constant law rho, r' = r'' = 0 exactly)."""
        ...

    @property
    def constant_radius(self) -> bool:
        """r' = 0 everywhere: chi = u, Mb = I, the circles centred on the axis with radius rho;
        the tube's fast path (closed forms, the 9-component frame fit) applies."""
        ...

    def fast_path(self) -> CurvatureLineSurface:
        """The same surface in the form that takes the fast path: a constant law's canal
        surface as the CurvatureLineTube of that radius, anything else itself."""
        ...

    def dispatch(self, tube: Callable[[CurvatureLineTube], T], canal: Callable[[CanalSurface], T]) -> T:
        """Double dispatch on the kind, for what only one kind can do: ``tube(t)`` with the
        tube that takes the fast path (the CurvatureLineTube itself, or a constant law's
        canal surface as :meth:`fast_path` gives it), else ``canal(self)`` (a varying law's
        CanalSurface). Returns what the called function returns."""
        ...

    # --- the net -----------------------------------------------------------------------
    def points(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """X(chi(u, s), s) = c + r (-r' t + q e), broadcast over u and s; shape + (3,)."""
        ...

    def grid(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """X on the grid u x s: shape (len(u), len(s), 3)."""
        ...

    def normal(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """The outward unit normal n = -r' t + q e (the sphere's; a tube: e)."""
        ...

    def derivatives(self, u: ArrayLike, s: ArrayLike) -> SurfaceDerivatives:
        """X and its partial derivatives in (u, s) up to second order (docs/MATH.md sections 7, 8)."""
        ...

    def fundamental_forms(self, u: ArrayLike, s: ArrayLike) -> FundamentalForms:
        """E, F, G, L, M, N at (u, s) from :meth:`derivatives` (F = M = 0: curvature lines)."""
        ...

    def offset(self, distance: float, *, allow_irregular: bool = False) -> CurvatureLineSurface:
        """The normal offset by ``distance``: the surface of r + distance on the same axis,
        with the same circles' planes and the same stringers chi(u, s)."""
        ...

    def inside(self, s: ArrayLike) -> FloatArray:
        """``s`` as a float array, checked to lie in the span (a ParameterError otherwise)."""
        ...

    def restricted(self, span: tuple[float, float]) -> CurvatureLineSurface:
        """The same surface over a sub-span, its stringers named by their angle at the
        sub-span's start (:meth:`stringer_angle` of this surface there converts)."""
        ...

    # --- the rings and the stringers ----------------------------------------------------
    def circle(self, s: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The ring at ``s``: (centre c - r r' t, radius r q, plane normal t)."""
        ...

    def moebius_matrix(self, s: ArrayLike) -> FloatArray:
        """Mb(s), shape s.shape + (2, 2): maps (sin(u/2), cos(u/2)) to a multiple of
        (sin(chi/2), cos(chi/2)); the identity where r' = 0."""
        ...

    def stringer_angle(self, u: ArrayLike, s: ArrayLike) -> FloatArray:
        """chi(u, s), the angle from r1(s) of the stringer u at ``s`` (a tube: u)."""
        ...

    def closing_angle(self, u: ArrayLike) -> FloatArray:
        """On a closed axis, the absolute angle chi(u, s1) + h (h the axis' holonomy) at which
        the stringer leaving the closing ring at ``u`` comes back to it (a tube: u + h)."""
        ...

    def s_breaks(self) -> FloatArray:
        """The span's ends and the s inside it where the surface is only C^k: the axis'
        joints and a radius law's breaks (a table's knots), sorted."""
        ...


def is_surface(value: object) -> TypeGuard[CurvatureLineSurface]:
    """Whether ``value`` is a curvature-line surface (a CurvatureLineTube or a CanalSurface)."""
    return isinstance(value, CurvatureLineSurface)
