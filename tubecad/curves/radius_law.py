"""Radius laws r(s) for canal surfaces (docs/MATH.md section 8).

A canal surface is the envelope of spheres of radius r(s) centred on the axis c(s); it
exists where |r'| < 1 and r > 0. A law is given as

- a number: a constant radius (r' = r'' = 0 exactly; the canal surface is today's tube);
- an expression in s (a string, parsed safely by :mod:`.expression`) or a Python callable
  of s: resolved as a piecewise Chebyshev series on the span, so r', r'', r''' are the
  series' exact derivatives;
- a table [[s0, r0], [s1, r1], ...] (s strictly increasing, covering the span): the cubic
  spline through the points with not-a-knot ends (C2; 2 points give a straight line,
  3 a parabola); on a closed axis a table whose last r repeats the first is the periodic
  cubic spline (C2 all round the loop, the closing point included).

On a closed axis the law must close: r(s1) = r(s0) and r'(s1) = r'(s0), so that the
characteristic circle at s1 is the one at s0 (:meth:`RadiusLaw.check_closes`).

Every law is checked on its span: r > 0 and |r'| < 1, each sampled densely and its worst
sample refined, else a one-line ParameterError naming the key and the s where it fails.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError
from tubecad.core.validation import bounded_length, finite_number, span_pair
from tubecad.curves.chebyshev import PiecewiseChebyshev
from tubecad.curves.expression import compile_expression

FloatArray = np.ndarray
RadiusValue = float | str | Callable[[np.ndarray], np.ndarray] | Sequence[Sequence[float]]

TABLE_INTERPOLATION = "cubic spline through the points, C2, not-a-knot ends (2 points: a straight line, 3: a parabola)"
PERIODIC_TABLE_INTERPOLATION = (
    "periodic cubic spline through the points (a closed axis: the last r repeats the "
    "first), C2 all round the loop, the closing point included"
)
#: on a closed axis r(s1) must equal r(s0) to this relative difference, and r'(s1) r'(s0) to CLOSING_SLOPE
CLOSING_RADIUS = 1e-9
CLOSING_SLOPE = 1e-8
#: samples per series panel or table interval when checking r > 0 and |r'| < 1
SAMPLES_PER_PIECE = 64


class RadiusLaw:
    """r(s) on ``span`` with its derivatives, all vectorised over arrays of s.

    ``kind`` is "constant", "expression", "callable" or "table"; ``breaks`` are the interior
    s where r is less smooth (a table's knots: r''' jumps there), for solvers to start
    panels at. Construct with :func:`radius_law`.

    Args:
        kind: ``"constant"``, ``"expression"``, ``"callable"`` or ``"table"``.
        span: the arc lengths (s0, s1) of the axis the law is on, model units.
        name: the law's name in messages and reports (the spec key, e.g. ``"radius"``).
        source: what the law was given as: the number, the expression, the callable or the
            table (an (n, 2) array of [s, r] rows).
        pieces: the callables of s giving r and its first three derivatives, or None for a
            constant law.
        breaks: the s where r is less smooth (a table's inner knots); those outside the open
            span are dropped. Default: none.
        resolution: how many pieces the law is checked on (sampled SAMPLES_PER_PIECE times
            each; at least one per break interval). Default 1.
        offset: the distance already added to the law by :meth:`shifted` (reported), model
            units. Default 0.
        periodic: whether the law is known to close round a closed axis (a periodic table).
            Default False.

    Raises:
        ParameterError: r <= 0 or |r'| >= 1 somewhere on the span, naming the law and the s.
    """

    def __init__(
        self,
        kind: str,
        span: tuple[float, float],
        name: str,
        source: Any,
        pieces: tuple[Callable[[np.ndarray], np.ndarray], ...] | None,
        *,
        breaks: Iterable[float] = (),
        resolution: int = 1,
        offset: float = 0.0,
        periodic: bool = False,
    ) -> None:
        self.kind, self.span, self.name, self.source, self.offset = kind, span, name, source, offset
        #: set once the law is known to close round a closed axis (a periodic table, or checked by check_closes)
        self.periodic = periodic
        self._pieces = pieces  # (r, r', r'', r''') or None for a constant
        self.breaks = np.asarray(sorted(b for b in breaks if span[0] < b < span[1]), dtype=float)
        self._resolution = max(resolution, len(self.breaks) + 1)  # pieces to sample SAMPLES_PER_PIECE times
        self._check()

    # --- evaluation --------------------------------------------------------------------
    @property
    def constant(self) -> bool:
        return self._pieces is None

    @property
    def value(self) -> float | None:
        """The radius of a constant law, else None."""
        return float(self.source) if self.constant else None

    @property
    def constant_value(self) -> float:
        """The radius of a constant law (:attr:`value`, typed for the callers that know the
        law is constant); a ValueError on a varying law."""
        if not self.constant:
            raise ValueError(f"{self.name}: a {self.kind} radius law has no constant value")
        return float(self.source)

    def _eval(self, order: int, s: ArrayLike) -> FloatArray:
        s = np.asarray(s, dtype=float)
        if self._pieces is None:
            return np.full(s.shape, float(self.source) if order == 0 else 0.0)
        return np.asarray(self._pieces[order](s), dtype=float) * np.ones(s.shape)

    def r(self, s: ArrayLike) -> FloatArray:
        """r(s)."""
        return self._eval(0, s)

    def dr(self, s: ArrayLike) -> FloatArray:
        """r'(s)."""
        return self._eval(1, s)

    def ddr(self, s: ArrayLike) -> FloatArray:
        """r''(s)."""
        return self._eval(2, s)

    def dddr(self, s: ArrayLike) -> FloatArray:
        """r'''(s) (a table's is piecewise constant)."""
        return self._eval(3, s)

    def shifted(self, distance: float) -> RadiusLaw:
        """r + ``distance`` (the law of the normal offset: same r', r'', same curvature-line net)."""
        d = finite_number("distance", distance)
        if self._pieces is None:
            return radius_law(float(self.source) + d, self.span, self.name)
        r, dr, ddr, dddr = self._pieces
        return RadiusLaw(
            self.kind,
            self.span,
            self.name,
            self.source,
            (lambda s: r(s) + d, dr, ddr, dddr),
            breaks=self.breaks,
            resolution=self._resolution,
            offset=self.offset + d,
            periodic=self.periodic,
        )

    def restricted(self, span: tuple[float, float]) -> RadiusLaw:
        """The same law on a sub-span (e.g. one stiffener's): the same r(s), checked there."""
        if self._pieces is None:
            return radius_law(float(self.source), span, self.name)
        return RadiusLaw(
            self.kind,
            span,
            self.name,
            self.source,
            self._pieces,
            breaks=self.breaks,
            resolution=self._resolution,
            offset=self.offset,
        )

    # --- checks ------------------------------------------------------------------------
    def check_closes(self) -> None:
        """On a closed axis the circle at s1 must be the circle at s0: r(s1) = r(s0) (to
        CLOSING_RADIUS relative) and r'(s1) = r'(s0) (to CLOSING_SLOPE), else a one-line
        ParameterError naming the law, the mismatch and where. A constant law closes."""
        if self.constant:
            return
        s0, s1 = self.span
        ends = np.array([s0, s1])
        (r0, r1), (d0, d1) = self.r(ends), self.dr(ends)
        dr_gap, slope_gap = abs(r1 - r0), abs(d1 - d0)
        if dr_gap > CLOSING_RADIUS * max(abs(r0), abs(r1)) or slope_gap > CLOSING_SLOPE:
            raise ParameterError(
                f"{self.name}: on a closed axis the law must close (r and r' at s = {s1:g} equal to "
                f"those at s = {s0:g}), but r = {r0:.10g}, r' = {d0:.6g} at s = {s0:g} and r = "
                f"{r1:.10g}, r' = {d1:.6g} at s = {s1:g} (they differ by {dr_gap:.3g} in r, "
                f"{slope_gap:.3g} in r'); give a periodic law, e.g. in cos(2 * pi * s / "
                f"{s1 - s0:.12g}), or open the axis (closed = false)"
            )
        self.periodic = True

    def _samples(self) -> np.ndarray:
        s0, s1 = self.span
        return np.union1d(np.linspace(s0, s1, max(2001, SAMPLES_PER_PIECE * self._resolution + 1)), self.breaks)

    def extreme(self, f: Callable[[np.ndarray], np.ndarray], largest: bool) -> tuple[float, float]:
        """(s, f(s)) at the smallest (or largest) value of ``f`` on the span (see :func:`refined_extreme`)."""
        return refined_extreme(f, self._samples(), largest, f"{self.name}: r(s)")

    def _check(self) -> None:
        if self.constant:
            self.min_radius, self.s_at_min_radius = float(self.source), self.span[0]
            self.max_radius, self.s_at_max_radius = float(self.source), self.span[0]
            self.max_slope, self.s_at_max_slope = 0.0, self.span[0]
            return
        s0, s1 = self.span
        self.s_at_min_radius, self.min_radius = self.extreme(self.r, largest=False)
        if not self.min_radius > 0.0:
            raise ParameterError(
                f"{self.name}: r reaches {self.min_radius:.6g} at s = {self.s_at_min_radius:.6g}; "
                f"the radius must stay > 0 over the span [{s0:g}, {s1:g}]"
            )
        self.s_at_max_radius, self.max_radius = self.extreme(self.r, largest=True)
        self.s_at_max_slope, self.max_slope = self.extreme(lambda x: np.abs(self.dr(x)), largest=True)
        if not self.max_slope < 1.0:
            raise ParameterError(
                f"{self.name}: |r'| reaches {self.max_slope:.6g} at s = {self.s_at_max_slope:.6g}; "
                "a canal surface needs |r'| < 1 (the spheres would not have an envelope)"
            )

    # --- report ------------------------------------------------------------------------
    def describe(self) -> dict[str, Any]:
        """The law for a report: kind, its input, interpolation (tables), extremes and where."""
        source = self.source
        if self.kind == "callable":
            source = repr(source)
        elif self.kind == "table":
            source = [[float(a), float(b)] for a, b in np.asarray(source)]
        out: dict[str, Any] = {"kind": self.kind, self.name: source, "s": list(self.span)}
        if self.kind == "table":
            out["interpolation"] = PERIODIC_TABLE_INTERPOLATION if self.periodic else TABLE_INTERPOLATION
        if self.periodic:
            out["periodic"] = "r(s1) = r(s0) and r'(s1) = r'(s0): the law closes round the closed axis"
        if self.offset:
            out["offset"] = self.offset
        out.update(
            {
                "min": self.min_radius,
                "s_at_min": self.s_at_min_radius,
                "max": self.max_radius,
                "s_at_max": self.s_at_max_radius,
                "max_abs_slope": self.max_slope,
                "s_at_max_abs_slope": self.s_at_max_slope,
            }
        )
        return out

    def __repr__(self) -> str:
        shown = self.source if self.kind != "table" else f"{len(self.source)} points"
        return f"RadiusLaw({self.kind}: {shown!r:.80}, span={self.span!r})"


def refined_extreme(
    f: Callable[[np.ndarray], np.ndarray], s: np.ndarray, largest: bool, name: str = "f"
) -> tuple[float, float]:
    """(s*, f(s*)) at the smallest (or largest) value of ``f`` over the sorted samples ``s``:
    the best sample, refined by a bounded scalar search between its neighbours (an extreme
    between two samples is found, not stepped over). A non-finite value is a ParameterError."""
    sign = -1.0 if largest else 1.0
    with np.errstate(all="ignore"):
        v = sign * np.asarray(f(s), dtype=float)
    bad = ~np.isfinite(v)
    if bad.any():
        i = int(np.argmax(bad))
        raise ParameterError(f"{name} is not finite at s = {s[i]:.6g}")
    i = int(np.argmin(v))
    best = (float(s[i]), float(v[i]))
    if 0 < i < len(s) - 1:
        from scipy.optimize import minimize_scalar  # at first use: a spec's check loads no scipy.optimize (0.1 s)

        res = minimize_scalar(
            lambda x: sign * float(f(np.array(x))),
            bounds=(s[i - 1], s[i + 1]),
            method="bounded",
            options={"xatol": 1e-12 * (s[-1] - s[0])},
        )
        if res.fun < best[1]:
            best = (float(res.x), float(res.fun))
    return best[0], sign * best[1]


def radius_law(
    value: RadiusValue | RadiusLaw, span: tuple[float, float], name: str = "radius", axis: Any = None
) -> RadiusLaw:
    """The radius law ``value`` (a number, an expression in s, a callable of s, or a table
    [[s, r], ...]) on ``span``, checked there; ParameterError naming ``name`` otherwise.
    With the ``axis``, an expression may also use x, y, z: the axis point c(s) (a Dupin
    cyclide's spheres have r = mu - (c/a) x).

    Args:
        value: the radius, model units: a number > 0 (or a numeric string: a constant law),
            an expression in ``s`` (and x, y, z with the ``axis``), a vectorised callable
            r(s), a table [[s, r], ...] (s strictly increasing, covering the span, r > 0:
            the not-a-knot cubic spline through it), or a :class:`RadiusLaw` on ``span``
            (returned as it is).
        span: the axis' arc lengths (s0, s1), model units, increasing.
        name: the key named in messages and reports (default ``"radius"``).
        axis: the :class:`~tubecad.curves.axis.Axis` the law is for, or None (default): with
            it an expression may use x, y, z, and on a closed axis a table is the periodic
            spline (its last r must repeat the first).

    Returns:
        The checked law: r > 0 and |r'| < 1 over the span.

    Raises:
        ExpressionError: an expression that is not a safe arithmetic expression.
        ParameterError: a value of another type, a bad table, a law on another span, or
            r <= 0 or |r'| >= 1 somewhere on the span, naming ``name`` and the s.
    """
    span = span_pair("span", span)
    if isinstance(value, RadiusLaw):
        if value.span != span:
            raise ParameterError(
                f"{name}: the law is given on [{value.span[0]:g}, {value.span[1]:g}], "
                f"the axis' span is [{span[0]:g}, {span[1]:g}]"
            )
        return value
    if isinstance(value, str):
        try:
            value = float(value)  # "3": a constant written as text
        except ValueError:
            pass
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        return RadiusLaw("constant", span, name, bounded_length(name, value, 0.0), None)
    if isinstance(value, str) or callable(value):
        return _series_law(value, span, name, axis)
    if isinstance(value, (list, tuple, np.ndarray)):
        return _table_law(value, span, name, periodic=bool(getattr(axis, "closed", False)))
    raise ParameterError(
        f"{name} must be a number, an expression in s, a callable r(s) or a table [[s, r], ...], got {value!r:.80}"
    )


def _series_law(
    value: str | Callable[[np.ndarray], np.ndarray], span: tuple[float, float], name: str, axis: Any = None
) -> RadiusLaw:
    """An expression (in s, and x, y, z of the axis point if the ``axis`` is given) or a
    callable, resolved as a Chebyshev series with exact derivatives."""
    text = value if isinstance(value, str) else None

    def coordinate(k: int) -> Callable[[np.ndarray], np.ndarray]:
        return lambda s: axis.position(s)[..., k]

    derived = None if axis is None else {c: coordinate(k) for k, c in enumerate("xyz")}
    func = compile_expression(value, name, derived=derived) if isinstance(value, str) else value

    def values(s: np.ndarray) -> np.ndarray:
        try:
            out = np.asarray(func(s))
        except Exception as exc:
            raise ParameterError(f"{name}(s) raised {type(exc).__name__}: {exc}"[:300]) from exc
        if out.dtype.kind not in "iuf":
            raise ParameterError(f"{name}(s) must return real numbers, got {out.dtype} values")
        try:
            return out.astype(float) * np.ones_like(s)
        except ValueError:
            raise ParameterError(
                f"{name}(s) must return an array shaped like s {np.shape(s)} or a scalar, got shape {out.shape}"
            ) from None

    r = PiecewiseChebyshev.fit(values, *span, name=f"{name}(s)")
    dr = r.derivative()
    ddr = dr.derivative()
    return RadiusLaw(
        "expression" if text is not None else "callable",
        span,
        name,
        value,
        (r, dr, ddr, ddr.derivative()),
        resolution=len(r.coeffs),
    )


def _table_law(
    value: Sequence[Sequence[float]], span: tuple[float, float], name: str, periodic: bool = False
) -> RadiusLaw:
    """The not-a-knot cubic spline through the rows [s, r] (strictly increasing s, r > 0);
    ``periodic`` (a closed axis): the periodic cubic spline, the rows running from the
    span's start to its end and the last r repeating the first (else refused, naming them)."""
    rows = list(value)
    if len(rows) < 2:
        raise ParameterError(f"{name}: a table needs at least 2 rows [s, r], got {len(rows)}")
    table: list[tuple[float, float]] = []
    for i, row in enumerate(rows):
        try:
            s_i, r_i = row
        except (TypeError, ValueError):
            raise ParameterError(f"{name}: table row {i} must be a pair [s, r], got {row!r:.80}") from None
        s_i = finite_number(f"{name} row {i} s", s_i)
        r_i = finite_number(f"{name} row {i} r", r_i)
        if not r_i > 0.0:
            raise ParameterError(f"{name}: r = {r_i:g} at s = {s_i:g} (row {i}); the radius must be > 0")
        if table and s_i <= table[-1][0]:
            what = "appears twice" if s_i == table[-1][0] else f"follows s = {table[-1][0]:g} (row {i - 1})"
            raise ParameterError(f"{name}: s = {s_i:g} (row {i}) {what}; the table's s must increase strictly")
        table.append((s_i, r_i))
    data = np.array(table)
    s0, s1 = span
    slack = 1e-9 * (s1 - s0)
    if data[0, 0] > s0 + slack or data[-1, 0] < s1 - slack:
        end = s0 if data[0, 0] > s0 + slack else s1
        raise ParameterError(
            f"{name}: the table covers s in [{data[0, 0]:g}, {data[-1, 0]:g}], which misses "
            f"s = {end:g} of the span [{s0:g}, {s1:g}]; its rows must reach both ends "
            "(no extrapolation)"
        )
    # only tables need it: importing tubecad.curves stays light
    from scipy.interpolate import CubicSpline

    if periodic:
        last = len(data) - 1
        if abs(data[0, 0] - s0) > slack or abs(data[-1, 0] - s1) > slack:
            raise ParameterError(
                f"{name}: on a closed axis the table must run from the span's start to its end (one "
                f"loop, [{s0:g}, {s1:g}]), but row 0 is at s = {data[0, 0]:g} and row {last} at s = "
                f"{data[-1, 0]:g}"
            )
        r0, r1 = data[0, 1], data[-1, 1]
        if len(data) < 3 or abs(r1 - r0) > CLOSING_RADIUS * max(r0, r1):
            why = (
                "it needs at least 3 rows"
                if len(data) < 3
                else f"row 0 has r = {r0:.10g} at s = {data[0, 0]:g} but row {last} has r = {r1:.10g} at s = "
                f"{data[-1, 0]:g}"
            )
            raise ParameterError(
                f"{name}: on a closed axis a table must close ({why}); make the last row's r "
                "equal the first's (the law is then the periodic cubic spline through the rows), "
                "or open the axis (closed = false)"
            )
        data[-1, 1] = r0  # exactly, as the periodic spline demands
        spline = CubicSpline(data[:, 0], data[:, 1], bc_type="periodic")
    else:
        spline = CubicSpline(data[:, 0], data[:, 1], bc_type="not-a-knot")
    pieces = tuple((lambda s, n=n: spline(s, n)) for n in range(4))
    return RadiusLaw("table", span, name, data, pieces, breaks=data[1:-1, 0], periodic=periodic)
