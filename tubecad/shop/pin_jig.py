"""Pin-jig tables (issue 13): the heights of the vertical pins a curved panel is set on.

The panel (the rings s_a < s_b, the stringers u_a < u_b of a wall surface S(u, s)) rests on a
square grid of pins standing on a flat jig plane; each pin touches the surface the pins
carry (the one opposite the stiffeners) where the pin's vertical line meets it.

- up = up_sign * m / |m|, m = Int Int S_u x S_s du ds the area-weighted mean outward normal
  (Gauss-Legendre); up_sign = +1 sets the panel dome-up (outward side up), -1 as a trough;
- x_dir = the axis tangent t(s_m) at the middle s_m = (s_a + s_b) / 2 made orthogonal to up,
  y_dir = up x x_dir (right-handed);
- the plane lies ``clearance`` below the patch's lowest point (the minimum of S . up over the
  patch, from the samples refined by bounded L-BFGS-B), so every height is >= clearance;
- the pin grid (spacing h) passes through the projection of the panel's middle point
  S(u_m, s_m), so there is always a pin; its (0, 0) (the table's ``origin``, on the plane) is
  the grid point of the smallest i and j among the pins, so i, j >= 0 and x = i h, y = j h;
- a grid point is a pin when its vertical line meets the patch: proj(S(u, s)) = (x, y) is
  solved for (u, s) by Newton from the nearest sample (scipy.spatial.cKDTree), the residual
  on the exact S, to 1e-12 of the panel's size, and kept when (u, s) lies in the panel's
  ranges; the height is (S(u, s) - origin) . up.

The panel must be a graph over the jig plane (the projected Jacobian keeps its sign: less
than half a tube, say); one that folds over it (a vertical line would meet it twice) is refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from tubecad.core.atomic import save_figure, write_text
from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.core.units import length_unit as length_unit_of
from tubecad.core.validation import finite_number
from tubecad.shop.panel_development import WallSurface, _panel_name, _s_breaks, check_panel

#: samples of the patch along each direction at most (the Newton starts, the bounds)
MAX_SAMPLES = 257
#: Newton iterations at most
MAX_ITERATIONS = 40


class JigTable(Protocol):
    """What a pin-jig picture shows: a tube panel's :class:`PinJig` or a net panel's
    (:class:`tubecad.shop.net_pin_jigs.CellPinJig`)."""

    @property
    def name(self) -> str: ...
    @property
    def spacing(self) -> float: ...
    @property
    def xy(self) -> np.ndarray: ...
    @property
    def heights(self) -> np.ndarray: ...
    @property
    def outline(self) -> np.ndarray: ...


@dataclass(frozen=True)
class PinJig:
    """A panel's pin-jig table: the plane (origin, x_dir, y_dir, up) and, per pin, its grid
    position ``xy`` in the plane, its height along ``up`` and where it touches the surface."""

    name: str
    spacing: float
    origin: np.ndarray  # (3,) the jig plane's origin (the pin grid's (0, 0))
    x_dir: np.ndarray
    y_dir: np.ndarray
    up: np.ndarray  # orthonormal, right-handed: the plane's axes and its upward normal
    xy: np.ndarray  # (n, 2) pin positions in the plane, i * spacing, j * spacing
    heights: np.ndarray  # (n,) pin heights above the plane, to the surface, along up
    angles_deg: np.ndarray  # (n,) where each pin touches the surface: u in degrees
    s: np.ndarray  # (n,) and s
    outline: np.ndarray  # (m, 2) the panel's boundary projected onto the plane

    @property
    def indices(self) -> np.ndarray:
        """(n, 2) the pins' grid indices (i, j)."""
        return np.rint(self.xy / self.spacing).astype(int)

    def points(self) -> np.ndarray:
        """(n, 3) the touching points origin + x x_dir + y y_dir + h up."""
        return self.origin + self.xy[:, :1] * self.x_dir + self.xy[:, 1:] * self.y_dir + self.heights[:, None] * self.up


def round_spacing(length: float, pins: int = 6) -> float:
    """A round pin spacing (1, 2 or 5 x 10^k) putting about ``pins`` pins along ``length``
    (the panel's shorter extent): the largest such value <= length / pins."""
    target = length / pins
    k = math.floor(math.log10(target))
    return float(max(m * 10.0**k for m in (1, 2, 5) if m * 10.0**k <= target))


def _spacing(value: Any) -> float:
    try:
        h = finite_number("pin_spacing", value)
    except ParameterError:
        h = math.nan
    if not h > 0.0:
        raise ParameterError(f"pin_spacing must be > 0 (a finite length, model units), got {value!r:.40}")
    return h


def _mean_normal(surface: WallSurface, u: tuple[float, float], breaks: np.ndarray) -> np.ndarray:
    """Int Int S_u x S_s du ds by Gauss-Legendre (16 nodes per panel of at most 45 deg, and per
    s panel between the ``breaks``, which run from the panel's first ring to its last)."""
    x, w = np.polynomial.legendre.leggauss(16)

    def nodes(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
        return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()

    uu, wu = nodes(np.linspace(u[0], u[1], max(1, math.ceil((u[1] - u[0]) / (math.pi / 4))) + 1))
    ss, ws = nodes(breaks)
    d = surface.derivatives(uu[:, None], ss[None, :])
    return np.einsum("ijk,i,j->k", np.cross(d.S_u, d.S_s), wu, ws)


def pin_jig(
    surface: WallSurface,
    s_range: tuple[float, float],
    angles_deg: tuple[float, float],
    spacing: float,
    up_sign: float = 1.0,
    clearance: float = 0.0,
    name: str = "panel",
) -> PinJig:
    """The pin-jig table of the panel of ``surface`` between the rings ``s_range`` and the
    stringers ``angles_deg`` (degrees; chi0 on a canal surface), pins every ``spacing``
    (module docstring)."""
    (s_a, s_b), (deg_a, deg_b) = check_panel(surface, s_range, angles_deg)
    h = _spacing(spacing)
    if up_sign not in (1, -1) or isinstance(up_sign, bool):
        raise ParameterError(f"up_sign must be +1 (dome up) or -1 (trough), got {up_sign!r:.40}")
    clearance = finite_number("clearance", clearance)
    if clearance < 0.0:
        raise ParameterError(f"clearance must be >= 0, got {clearance:g}")
    name = _panel_name(name)
    u_a, u_b = math.radians(deg_a), math.radians(deg_b)
    u_m, s_m = 0.5 * (u_a + u_b), 0.5 * (s_a + s_b)

    mean = _mean_normal(surface, (u_a, u_b), _s_breaks(surface, (s_a, s_b)))
    mid = surface.derivatives(u_m, s_m)
    area_scale = float(np.linalg.norm(np.cross(mid.S_u, mid.S_s))) * (u_b - u_a) * (s_b - s_a)
    if np.linalg.norm(mean) < 1e-6 * area_scale:
        raise ParameterError("angles_deg: the panel has no mean normal (it goes round the surface); split it")
    up = float(up_sign) * mean / np.linalg.norm(mean)
    t = surface.axis.rotation_minimising_frame(s_m)[0]
    x_dir = t - float(t @ up) * up
    if np.linalg.norm(x_dir) < 1e-6:
        raise ParameterError("angles_deg: the panel's mean normal is along the axis; no stringer direction for x")
    x_dir /= np.linalg.norm(x_dir)
    y_dir = np.cross(up, x_dir)
    ref = mid.S
    frame = np.stack([x_dir, y_dir, up])

    # samples: Newton starts, the graph check, the lowest point, the bounding box
    ring, along = float(np.linalg.norm(mid.S_u)) * (u_b - u_a), float(np.linalg.norm(mid.S_s)) * (s_b - s_a)
    n_u = int(np.clip(math.ceil(4.0 * ring / h) + 1, 33, MAX_SAMPLES))
    n_s = int(np.clip(math.ceil(4.0 * along / h) + 1, 33, MAX_SAMPLES))
    us, ss = np.linspace(u_a, u_b, n_u), np.linspace(s_a, s_b, n_s)
    d = surface.derivatives(us[:, None], ss[None, :])
    local = (d.S - ref) @ frame.T  # (n_u, n_s, 3): x, y, height above ref
    jac = np.einsum("...i,...i", d.S_u, x_dir) * np.einsum("...i,...i", d.S_s, y_dir) - np.einsum(
        "...i,...i", d.S_s, x_dir
    ) * np.einsum("...i,...i", d.S_u, y_dir)
    if not (np.all(jac > 0) or np.all(jac < 0)):
        raise ParameterError(
            "angles_deg: the panel is not a graph over the jig plane (a vertical pin would meet "
            "it twice, or graze it); split it into smaller panels"
        )
    low = _lowest(surface, up, ref, local[..., 2], us, ss)
    size = float(np.ptp(local[..., :2].reshape(-1, 2), axis=0).max())

    # candidate grid points (a margin of one spacing round the sampled box), Newton on each
    lo, hi = local[..., :2].reshape(-1, 2).min(axis=0), local[..., :2].reshape(-1, 2).max(axis=0)
    i_rng = np.arange(math.floor(lo[0] / h) - 1, math.ceil(hi[0] / h) + 2)
    j_rng = np.arange(math.floor(lo[1] / h) - 1, math.ceil(hi[1] / h) + 2)
    ii, jj = (a.ravel() for a in np.meshgrid(i_rng, j_rng, indexing="ij"))
    targets = np.stack([ii * h, jj * h], axis=1)
    from scipy.spatial import cKDTree

    cell = math.hypot(*np.abs(np.diff(local[..., :2], axis=0)).max(axis=(0, 1))) + math.hypot(
        *np.abs(np.diff(local[..., :2], axis=1)).max(axis=(0, 1))
    )
    dist, nearest = cKDTree(local[..., :2].reshape(-1, 2)).query(targets)
    near = dist <= 2.0 * cell
    targets, ii, jj, nearest = targets[near], ii[near], jj[near], nearest[near]
    u0, s0 = us[nearest // n_s], ss[nearest % n_s]
    u, s, ok = _project(surface, ref, x_dir, y_dir, targets, u0, s0, (u_a, u_b), 1e-12 * max(size, h))
    slack_u, slack_s = 1e-9 * (u_b - u_a), 1e-9 * (s_b - s_a)
    keep = ok & (u >= u_a - slack_u) & (u <= u_b + slack_u) & (s >= s_a - slack_s) & (s <= s_b + slack_s)
    ii, jj, u, s = ii[keep], jj[keep], u[keep], s[keep]
    order = np.lexsort((ii, jj))
    ii, jj, u, s = ii[order], jj[order], u[order], s[order]
    i0, j0 = int(ii.min()), int(jj.min())  # the pin at u_m, s_m is always there
    origin = ref + (i0 * h) * x_dir + (j0 * h) * y_dir + (low - clearance) * up
    touching = surface.points(u, s)
    heights = (touching - origin) @ up
    outline = _outline(surface, (u_a, u_b), (s_a, s_b)) - origin
    return PinJig(
        name,
        h,
        origin,
        x_dir,
        y_dir,
        up,
        np.stack([(ii - i0) * h, (jj - j0) * h], axis=1).astype(float),
        heights,
        np.degrees(u),
        s,
        outline @ np.stack([x_dir, y_dir]).T,
    )


def _lowest(
    surface: WallSurface, up: np.ndarray, ref: np.ndarray, height: np.ndarray, us: np.ndarray, ss: np.ndarray
) -> float:
    """min (S - ref) . up over the patch: the lowest sample refined by bounded L-BFGS-B."""
    from scipy.optimize import minimize

    i, j = np.unravel_index(int(np.argmin(height)), height.shape)
    scale = max(float(np.ptp(height)), 1e-300)

    def f(x: np.ndarray) -> tuple[float, np.ndarray]:
        d = surface.derivatives(x[0], x[1])
        return float((d.S - ref) @ up) / scale, np.array([float(d.S_u @ up), float(d.S_s @ up)]) / scale

    res = minimize(
        f,
        np.array([us[i], ss[j]]),
        jac=True,
        method="L-BFGS-B",
        bounds=[(us[0], us[-1]), (ss[0], ss[-1])],
        options={"ftol": 1e-15, "gtol": 1e-13, "maxiter": 200},
    )
    return min(float(height[i, j]), float(res.fun) * scale)


def _project(
    surface: WallSurface,
    ref: np.ndarray,
    x_dir: np.ndarray,
    y_dir: np.ndarray,
    targets: np.ndarray,
    u: np.ndarray,
    s: np.ndarray,
    u_range: tuple[float, float],
    tol: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton on ((S - ref) . x_dir, (S - ref) . y_dir) = targets from (u, s); s kept in the
    axis' span, u within one panel width of the panel. Once every residual is below ``tol``
    one more step takes them to round-off (quadratic convergence). Returns (u, s, converged)."""
    span_lo, span_hi = surface.span
    width = u_range[1] - u_range[0]
    u, s = u.astype(float).copy(), s.astype(float).copy()
    done = np.zeros(len(u), dtype=bool)
    polished = False
    for _ in range(MAX_ITERATIONS):
        d = surface.derivatives(u, s)
        rel = d.S - ref
        r0, r1 = rel @ x_dir - targets[:, 0], rel @ y_dir - targets[:, 1]
        done = np.hypot(r0, r1) <= tol
        if polished:
            break
        polished = bool(done.all())
        a, b, c, e = d.S_u @ x_dir, d.S_s @ x_dir, d.S_u @ y_dir, d.S_s @ y_dir
        det = a * e - b * c
        with np.errstate(divide="ignore", invalid="ignore"):
            du, ds = (e * r0 - b * r1) / det, (a * r1 - c * r0) / det
        step = np.isfinite(du) & np.isfinite(ds)
        u = np.where(step, np.clip(u - np.where(step, du, 0.0), u_range[0] - width, u_range[1] + width), u)
        s = np.where(step, np.clip(s - np.where(step, ds, 0.0), span_lo, span_hi), s)
    return u, s, done


def _outline(surface: WallSurface, u: tuple[float, float], s: tuple[float, float], n: int = 65) -> np.ndarray:
    """The patch's boundary (ring s_a, seam u_b, ring s_b back, seam u_a back) in 3-D, (m, 3)."""
    uu, ss = np.linspace(*u, n), np.linspace(*s, n)
    edges = [
        surface.points(uu, s[0]),
        surface.points(u[1], ss[1:]),
        surface.points(uu[-2::-1], s[1]),
        surface.points(u[0], ss[-2:0:-1]),
    ]
    return np.concatenate(edges)


def write_pin_jig_csv(jig: PinJig, path: str | Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> Path:
    """The table as CSV: a comment line ``# units: mm``, the header pin, i, j, x, y, height,
    u_deg, s and one row per pin (numbered from 1), floats as repr (round-trip exact);
    written atomically."""
    unit = length_unit_of(length_unit)
    lines = [f"# units: {unit.name}", "pin,i,j,x,y,height,u_deg,s"]
    for k, ((i, j), (x, y), height, u, s) in enumerate(zip(jig.indices, jig.xy, jig.heights, jig.angles_deg, jig.s)):
        lines.append(",".join([str(k + 1), str(i), str(j)] + [repr(float(v)) for v in (x, y, height, u, s)]))
    return write_text(path, "\n".join(lines) + "\n")


#: pins whose heights the picture writes beside them (more: colours only)
MAX_LABELLED_PINS = 150


def write_pin_jig_picture(jig: JigTable, folder: str | Path, formats: tuple[str, ...] = ("png", "svg")) -> list[Path]:
    """``NAME_pin_jig.png`` and ``.svg`` (``formats``): the pins coloured by height, each height written at its
    pin, the panel's projected outline, equal aspect."""
    from matplotlib.figure import Figure  # no pyplot: the user's backend is left alone

    fig = Figure(figsize=(9, 8))
    ax = fig.subplots()
    closed = np.vstack([jig.outline, jig.outline[:1]])
    ax.plot(closed[:, 0], closed[:, 1], color="#10203a", linewidth=1.0)
    dots = ax.scatter(jig.xy[:, 0], jig.xy[:, 1], c=jig.heights, cmap="viridis", s=18, zorder=3)
    fig.colorbar(dots, ax=ax, shrink=0.8, label="pin height")
    size = max(3.0, min(7.0, 300.0 / math.sqrt(max(len(jig.heights), 1))))
    if len(jig.heights) <= MAX_LABELLED_PINS:  # beyond, the labels are unreadable (and slow): the CSV has them
        for (x, y), height in zip(jig.xy, jig.heights):
            ax.annotate(f"{height:.1f}", (x, y), xytext=(0, 4), textcoords="offset points", ha="center", fontsize=size)
    ax.set_aspect("equal")
    ax.set_title(
        f"{jig.name}: pin jig, spacing {jig.spacing:g}, {len(jig.heights)} pins, heights "
        f"{jig.heights.min():.4g} to {jig.heights.max():.4g}",
        fontsize=9,
    )
    return save_figure(fig, folder, f"{jig.name}_pin_jig", formats, dpi=110)
