"""Adaptive piecewise Chebyshev series: accurate quadrature for any smooth k(s).

A function on [a, b] is resolved panel by panel: on each panel it is interpolated at
Chebyshev-Lobatto points and the panel is halved until the series' tail is below
``tol`` times the function's scale. Integrating the series term by term (numpy's chebint)
then gives antiderivatives accurate to round-off (~1e-14 relative), which is how the
custom-curvature axis reaches closed-form accuracy (docs/MATH.md section 1). Values may be
vectors (a curve x(t) in 3-D, a frame): the coefficients then carry trailing axes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.polynomial import chebyshev as C
from numpy.typing import ArrayLike

from tubecad.core.errors import ParameterError

FloatFunction = Callable[[np.ndarray], np.ndarray]

#: points per panel from which a panel's points are evaluated together (fewer: each with its own gathers)
GROUPED_POINTS = 200  # measured: the crossover is at 150-200 points per panel
#: points evaluated together outside the grouped path (bounds the gathered coefficients' memory)
BLOCK_POINTS = 4096


class PiecewiseChebyshev:
    """f(x) on [breaks[0], breaks[-1]]: Chebyshev coefficients ``coeffs[i]`` on panel i,
    shape (panels, degree + 1, *value_shape)."""

    def __init__(self, breaks: np.ndarray, coeffs: np.ndarray) -> None:
        self.breaks = np.asarray(breaks, dtype=float)
        self.coeffs = np.asarray(coeffs, dtype=float)

    @classmethod
    def fit(
        cls,
        f: FloatFunction,
        a: float,
        b: float,
        *,
        name: str = "f",
        degree: int = 24,
        tol: float = 1e-15,
        max_panels: int = 2048,
        breaks: np.ndarray | None = None,
        parts: Sequence[tuple[int, float]] | None = None,
        floor: float = 0.0,
    ) -> PiecewiseChebyshev:
        """Resolve ``f`` on [a, b] adaptively, starting from the panels between ``breaks``
        (e.g. a spline's knots; default [a, b]). ``f`` takes an array of x (panels, nodes),
        each row one panel's nodes, and returns an array of that shape, or of that shape + a
        value shape (vectors: all resolved).

        ``parts``: (count, tol) for consecutive runs of the (flattened) values, each tested
        on its own: a panel is resolved when, for every part, its last four coefficients are
        below 10 tol scale, scale = the part's largest |value| so far (values of different
        sizes stacked in one fit: a position, a unit frame, curvatures). Default: all values
        one part, with ``tol``. ``floor``: the least scale (values that stay far below it, a
        nearly straight line's curvature, are resolved to ``tol`` of it, not of themselves,
        whose round-off they would have to resolve)."""
        nodes = np.cos(np.pi * np.arange(degree + 1) / degree)[::-1]  # Lobatto, ascending
        edges = np.asarray([a, b] if breaks is None else breaks, dtype=float)
        todo = list(zip(edges[:-1], edges[1:]))
        done: list[tuple[float, float, np.ndarray]] = []
        scales: np.ndarray | None = None
        while todo:
            lo = np.array([p[0] for p in todo])
            hi = np.array([p[1] for p in todo])
            x = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * nodes
            with np.errstate(all="ignore"):
                y = np.asarray(f(x), dtype=float)
                y = y * np.ones(x.shape + y.shape[x.ndim :])
            bad = ~np.isfinite(y)
            if bad.any():
                where = np.argwhere(bad)[0]
                raise ParameterError(f"{name} is not finite at s = {x[tuple(where[:2])]:.6g} (got {y[tuple(where)]})")
            value_shape = y.shape[2:]
            counts, tols = _parts(parts, int(np.prod(value_shape)), tol)
            starts = [sum(counts[:i]) for i in range(len(counts))]  # each part's first value
            largest = np.maximum.reduceat(np.abs(y).reshape(-1, sum(counts)).max(axis=0), starts)
            scales = np.maximum(largest if scales is None else np.maximum(scales, largest), max(floor, 1e-300))
            flat = np.moveaxis(y, 1, 0).reshape(degree + 1, -1)  # nodes x (panels * values)
            coeffs = np.moveaxis(C.chebfit(nodes, flat, degree).reshape(degree + 1, len(todo), *value_shape), 0, 1)
            tails = np.maximum.reduceat(np.abs(coeffs[:, -4:]).max(axis=1).reshape(len(todo), -1), starts, axis=1)
            resolved = (tails <= tols * scales * 10 + 1e-300).all(axis=1)
            next_todo = []
            for i, (l, h) in enumerate(todo):
                if resolved[i] or (h - l) <= 1e-12 * (b - a):
                    done.append((l, h, coeffs[i]))
                else:
                    m = 0.5 * (l + h)
                    next_todo += [(l, m), (m, h)]
            if len(done) + len(next_todo) > max_panels:
                lo_w, hi_w = min(next_todo, key=lambda p: p[1] - p[0])  # where the halving went deepest
                raise ParameterError(
                    f"{name} could not be resolved to {tols.min():g} with {max_panels} panels on "
                    f"[{a:g}, {b:g}]: it must be smooth and finite there, and it is not near "
                    f"s = {0.5 * (lo_w + hi_w):.6g} (a pole, a jump or a kink?)"
                )
            todo = next_todo
        done.sort(key=lambda p: p[0])
        breaks = np.array([p[0] for p in done] + [done[-1][1]])
        return cls(breaks, np.array([p[2] for p in done]))

    @classmethod
    def stack(cls, series: Sequence[PiecewiseChebyshev]) -> PiecewiseChebyshev:
        """Series on the same breaks as one, their values stacked on a new first value axis
        (value shape (len(series), *value_shape)); a lower degree is padded with zero terms,
        so one evaluation gives them all (e.g. x, x', x'')."""
        terms = max(f.coeffs.shape[1] for f in series)
        padded = [
            np.pad(f.coeffs, [(0, 0), (0, terms - f.coeffs.shape[1])] + [(0, 0)] * (f.coeffs.ndim - 2)) for f in series
        ]
        return cls(series[0].breaks, np.stack(padded, axis=2))

    def part(self, start: int, stop: int) -> PiecewiseChebyshev:
        """The values [start:stop] of a series with one value axis, as a series of its own."""
        return PiecewiseChebyshev(self.breaks, np.ascontiguousarray(self.coeffs[:, :, start:stop]))

    @property
    def value_shape(self) -> tuple[int, ...]:
        return self.coeffs.shape[2:]

    def locate(self, x: ArrayLike) -> np.ndarray:
        """The panel of each x (a point on a break: the panel starting there)."""
        return np.clip(np.searchsorted(self.breaks, x, side="right") - 1, 0, len(self.coeffs) - 1)

    def rows(self, x: ArrayLike) -> np.ndarray:
        """Evaluate ``x`` (..., n) row by row, each row on the panel of its middle point: for
        the nodes of one panel of a fit (its ends on breaks, maybe a rounding beyond), which
        would otherwise be taken from the neighbouring panels, whose series agree only to
        their accuracy (a jump there stops a fit's tail test from resolving)."""
        x = np.asarray(x, dtype=float)
        panel = self.locate(x[..., x.shape[-1] // 2])
        return self(x, np.broadcast_to(panel[..., None], x.shape))

    def __call__(self, x: ArrayLike, panel: np.ndarray | None = None) -> np.ndarray:
        """Evaluate at ``x`` (any shape; result x.shape + value_shape): f(x) = sum_j c_j T_j(z),
        z the point mapped onto its panel's [-1, 1] (``panel``: each point's, default
        :meth:`locate`). Where many points share a panel, panel by panel (numpy's chebval,
        Clenshaw's recurrence); otherwise over all points at once, each with its panel's
        coefficients, in blocks."""
        x = np.asarray(x, dtype=float)
        flat = x.ravel()
        panel = self.locate(flat) if panel is None else np.asarray(panel).ravel()
        coeffs = self.coeffs.reshape(self.coeffs.shape[0], self.coeffs.shape[1], -1)  # values flattened
        lo, hi = self.breaks[panel], self.breaks[panel + 1]
        z = (2.0 * flat - lo - hi) / (hi - lo)
        if flat.size < GROUPED_POINTS * np.count_nonzero(np.bincount(panel)):
            out = np.empty((flat.size, coeffs.shape[2]))
            for a in range(0, flat.size, BLOCK_POINTS):
                block = slice(a, a + BLOCK_POINTS)
                out[block] = _clenshaw(z[block], coeffs[panel[block]])
        else:
            order = np.argsort(panel, kind="stable")
            panels, starts = np.unique(panel[order], return_index=True)
            out = np.empty((flat.size, coeffs.shape[2]))
            for k, a, b in zip(panels, starts, np.append(starts[1:], flat.size)):
                rows = order[a:b]
                out[rows] = C.chebval(z[rows], coeffs[k]).T
        return out.reshape(x.shape + self.value_shape)

    def antiderivative(self, value_at_start: float | np.ndarray = 0.0) -> PiecewiseChebyshev:
        """The continuous antiderivative F with F(breaks[0]) = value_at_start."""
        half_widths = 0.5 * np.diff(self.breaks)
        integ = np.array([C.chebint(c, lbnd=-1.0, scl=h) for c, h in zip(self.coeffs, half_widths)])
        panel_totals = integ.sum(axis=1)  # F(panel end) - F(panel start), as T_j(1) = 1
        zero = np.zeros((1,) + self.value_shape)
        offsets = np.asarray(value_at_start, dtype=float) + np.concatenate([zero, np.cumsum(panel_totals, axis=0)[:-1]])
        integ[:, 0] += offsets
        return PiecewiseChebyshev(self.breaks, integ)

    def derivative(self) -> PiecewiseChebyshev:
        """dF/dx, panel by panel (one degree lower)."""
        half_widths = 0.5 * np.diff(self.breaks)
        return PiecewiseChebyshev(
            self.breaks, np.array([C.chebder(c, scl=1.0 / h) for c, h in zip(self.coeffs, half_widths)])
        )


def _clenshaw(z: np.ndarray, coeffs: np.ndarray) -> np.ndarray:
    """sum_j c_j T_j(z) by Clenshaw's recurrence b_j = c_j + 2 z b_{j+1} - b_{j+2}, f = c_0 +
    z b_1 - b_2, for points z (n,) each with its own coefficients (n, terms, values): one
    gather for all terms, the recurrence on views, in place (it is backward stable; a sum
    of T_j from their own recurrence was measured noisier, which the adaptive fit's tail
    test then took for an unresolved panel)."""
    b1 = np.zeros((coeffs.shape[0], coeffs.shape[2]))
    b2 = np.zeros_like(b1)
    twice = 2.0 * z[:, None]
    for j in range(coeffs.shape[1] - 1, 0, -1):
        b2 *= -1.0
        b2 += coeffs[:, j]
        b2 += twice * b1
        b1, b2 = b2, b1
    return coeffs[:, 0] + z[:, None] * b1 - b2


def _parts(parts: Sequence[tuple[int, float]] | None, values: int, tol: float) -> tuple[list[int], np.ndarray]:
    """(counts, tolerances) of :meth:`PiecewiseChebyshev.fit`'s parts, checked to cover the values."""
    if parts is None:
        return [values], np.array([tol])
    counts = [int(n) for n, _ in parts]
    if sum(counts) != values:
        raise ValueError(f"parts cover {sum(counts)} values, the function has {values}")
    return counts, np.array([float(t) for _, t in parts])
