"""Web pieces nested on stock plates (issue 13), checked with shapely.

Each piece may be turned (never mirrored, so that its marked side stays up): its
minimum-area rectangle laid along the plate's length, then turned by 0, 180, 90 or 270 deg.
Pieces are placed largest first by a raster bottom-left fill: the usable plate (less a kerf
at each edge) is a grid of RASTER_CELLS cells along its length; every placed piece marks
the cells within 2 kerf + 1.5 cells of it, and a new piece goes where its own cells meet
none of those (one FFT correlation per turn, scipy.signal.fftconvolve) with its top edge
lowest, then leftmost; each such spot is checked exactly with shapely (distance >= 2 kerf
to every placed piece, inside the plate less a kerf) before it is taken. A new plate is
opened when no plate has room. Pieces nest inside ring annuli and curved strips inside
each other. :func:`check_nesting` measures the plates with shapely, independently.

A plate's utilisation is the pieces' area over the material the nest uses: the bottom-left
fill leaves the plate's upper part free, one strip the plate's length, which goes back to
stock as an offcut when it is wide enough (:data:`OFFCUT_MIN`); the used strip is the rest.
A few small webs on a large plate thus read as the share of the strip they take, not of
the plate (which is reported too, ``plate_utilisation``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.shop.fabrication import Fabrication
from tubecad.shop.webs import WebPiece

#: the rest of a plate's width above its nest is an offcut back to stock if at least this
#: fraction of the width, else scrap (the whole plate counts as used)
OFFCUT_MIN = 0.2


@dataclass(frozen=True)
class PlacedPiece:
    """A piece on a plate: its own outline turned by ``angle`` (radians, counter-clockwise)
    about the origin, then moved by ``offset``."""

    piece: WebPiece
    angle: float
    offset: tuple[float, float]

    def place(self, points: np.ndarray) -> np.ndarray:
        """Points of the piece's own frame on the plate."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        return np.asarray(points) @ np.array([[c, s], [-s, c]]) + np.asarray(self.offset)

    @property
    def outline(self) -> np.ndarray:
        return self.place(self.piece.pattern.outline)

    @property
    def hole(self) -> np.ndarray | None:
        hole = self.piece.pattern.hole
        return None if hole is None else self.place(hole)

    def polygon(self):
        """The placed piece as a shapely Polygon (a full ring's annulus with its hole)."""
        from shapely.geometry import Polygon

        hole = self.hole
        return Polygon(self.outline, [] if hole is None else [hole])


@dataclass
class Plate:
    """A stock plate and the pieces nested on it, a kerf or more from its edges."""

    index: int  # 1, 2, ...
    size: tuple[float, float]  # (length, width): x along the length
    pieces: list[PlacedPiece] = field(default_factory=list)
    kerf: float = 0.0  # the margin kept from the plate's edges

    @property
    def name(self) -> str:
        return f"plate_{self.index:02d}"

    @property
    def used_size(self) -> tuple[float, float]:
        """(length, width) of the strip the nest uses: the plate's whole length, across its
        width to a kerf past the highest piece (the nest fills the plate from its lower long
        edge up, so the rest of the width is one strip, an offcut back to stock); the whole
        plate if that offcut would be narrower than OFFCUT_MIN of the plate's width (scrap)."""
        top = max((_top(p) for p in self.pieces), default=0.0)
        used = min(self.size[1], top + self.kerf)
        return self.size[0], used if self.size[1] - used >= OFFCUT_MIN * self.size[1] else self.size[1]

    @property
    def utilisation(self) -> float:
        """The pieces' exact area over the used strip's (:attr:`used_size`)."""
        length, width = self.used_size
        return self.area / (length * width) if width > 0.0 else 0.0

    @property
    def plate_utilisation(self) -> float:
        """The pieces' exact area over the whole plate's."""
        return self.area / (self.size[0] * self.size[1])

    @property
    def area(self) -> float:
        """The pieces' exact area."""
        return sum(p.piece.area for p in self.pieces)


def oriented(piece: WebPiece) -> tuple[float, np.ndarray, np.ndarray]:
    """(angle, lower-left corner, size) of the piece turned so that the long side of its
    minimum-area rectangle lies along x (for a full ring: unturned)."""
    from shapely.geometry import Polygon

    outline = piece.pattern.outline
    angle = 0.0
    if piece.pattern.hole is None:
        rect = np.asarray(Polygon(outline).minimum_rotated_rectangle.exterior.coords)[:4]
        edge = (
            rect[1] - rect[0]
            if np.linalg.norm(rect[1] - rect[0]) >= np.linalg.norm(rect[2] - rect[1])
            else rect[2] - rect[1]
        )
        angle = -math.atan2(edge[1], edge[0])
    c, s = math.cos(angle), math.sin(angle)
    turned = outline @ np.array([[c, s], [-s, c]])
    lo, hi = turned.min(axis=0), turned.max(axis=0)
    if piece.pattern.hole is not None or piece.pattern.sector is not None:
        pad = _arc_pad(outline)  # a ring's arcs are exact in the DXF: they bulge past the sampled outline
        lo, hi = lo - pad, hi + pad
    return angle, lo, hi - lo


#: raster cells along the plate's usable length (the placement search's resolution)
RASTER_CELLS = 600
#: turns tried for each piece, after its minimum-area rectangle is laid along the plate
TURNS_DEG = (0.0, 180.0, 90.0, 270.0)


def nest(pieces: list[WebPiece], fab: Fabrication) -> list[Plate]:
    """The pieces on as few plates as a raster bottom-left fill finds (module docstring)."""
    length, width = sorted(fab.plate_size, reverse=True)
    margin, spacing = fab.kerf, 2 * fab.kerf
    usable = (length - 2 * margin, width - 2 * margin)
    cell = usable[0] / RASTER_CELLS
    shape = (int(usable[1] // cell), int(usable[0] // cell))  # rows along y, columns along x
    plates: list[Plate] = []
    occupied: list[np.ndarray] = []
    order = sorted(pieces, key=lambda p: (-_footprint(p), p.name))
    for piece in order:
        candidates = _turned(piece, usable)
        for k, plate in enumerate(plates + [None]):
            if plate is None:
                plates.append(Plate(len(plates) + 1, (length, width), kerf=fab.kerf))
                occupied.append(np.zeros(shape, dtype=bool))
                plate = plates[-1]
            spot = _lowest_spot(plate, occupied[k], piece, candidates, cell, margin, spacing)
            if spot is not None:
                placed, mask, (row, col) = spot
                plate.pieces.append(placed)
                _paint(occupied[k], mask, row, col)
                break
            if not plate.pieces:
                raise ParameterError(
                    f"plate_size {list(fab.plate_size)} is too small for {piece.name} "
                    f"with a kerf of {fab.kerf:g} at its edges",
                    key="plate_size",
                )
    return plates


def _paint(occupied: np.ndarray, mask: np.ndarray, row: int, col: int) -> None:
    """OR ``mask`` into ``occupied`` with its corner at (row, col), clipped to the raster."""
    r0, c0 = max(row, 0), max(col, 0)
    r1, c1 = min(row + mask.shape[0], occupied.shape[0]), min(col + mask.shape[1], occupied.shape[1])
    if r1 > r0 and c1 > c0:
        occupied[r0:r1, c0:c1] |= mask[r0 - row : r1 - row, c0 - col : c1 - col]


def _footprint(piece: WebPiece) -> float:
    _, _, size = oriented(piece)
    return float(size[0] * size[1])


def _turned(piece: WebPiece, usable: tuple[float, float]) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(angle, lower-left, size) of each turn of the piece that fits the usable plate."""
    angle, _, _ = oriented(piece)
    out = []
    for turn in TURNS_DEG:
        a = angle + math.radians(turn)
        c, s = math.cos(a), math.sin(a)
        outline = piece.pattern.outline @ np.array([[c, s], [-s, c]])
        lo, hi = outline.min(axis=0), outline.max(axis=0)
        if piece.pattern.hole is not None or piece.pattern.sector is not None:
            pad = _arc_pad(piece.pattern.outline)
            lo, hi = lo - pad, hi + pad
        if hi[0] - lo[0] <= usable[0] and hi[1] - lo[1] <= usable[1]:
            out.append((a, lo, hi - lo))
    return out


def _arc_pad(outline: np.ndarray) -> float:
    """How far a ring's exact arcs bulge past its sampled outline (twice the sagitta)."""
    r_out = float(np.linalg.norm(outline, axis=1).max())
    step = np.max(np.abs(np.diff(np.unwrap(np.arctan2(outline[:, 1], outline[:, 0])))))
    return 2.0 * r_out * (1.0 - math.cos(min(step, math.pi / 2) / 2))


def _mask(polygon, lo: np.ndarray, rows: int, cols: int, cell: float, grow: float) -> np.ndarray:
    """Cells (of the raster anchored at ``lo``) within ``grow`` of the polygon."""
    import shapely

    x = lo[0] + (np.arange(cols) + 0.5) * cell
    y = lo[1] + (np.arange(rows) + 0.5) * cell
    xx, yy = np.meshgrid(x, y)
    region = polygon.buffer(grow, quad_segs=4)
    shapely.prepare(region)
    return shapely.contains_xy(region, xx, yy)


def _lowest_spot(
    plate: Plate, occupied: np.ndarray, piece: WebPiece, candidates, cell: float, margin: float, spacing: float
):
    """The placement of ``piece`` (one of its turns) whose top edge is lowest, then leftmost,
    among the raster positions where its cells meet no cell within spacing + 1.5 cells of
    a placed piece; each is checked exactly (shapely distances) before it is taken.
    Returns (placed, its grown mask, the mask's (row, col) on the raster) or None."""
    from scipy.signal import fftconvolve

    tries = []
    for angle, lo, size in candidates:
        rows, cols = int(math.ceil(size[1] / cell)), int(math.ceil(size[0] / cell))
        if rows > occupied.shape[0] or cols > occupied.shape[1]:
            continue
        polygon = PlacedPiece(piece, angle, (0.0, 0.0)).polygon()
        mask = _mask(polygon, lo, rows, cols, cell, 0.75 * cell)
        if occupied.any():
            hits = fftconvolve(occupied.astype(float), mask[::-1, ::-1].astype(float), mode="valid") > 0.5
        else:
            hits = np.zeros((occupied.shape[0] - rows + 1, occupied.shape[1] - cols + 1), dtype=bool)
        free = np.argwhere(~hits)
        if len(free):
            free = free[np.lexsort((free[:, 1], free[:, 0] + rows))][:64]  # lowest top edge, then leftmost
            tries += [(row + rows, col, row, angle, lo, size) for row, col in free]
    tries.sort(key=lambda t: (t[0], t[1]))
    for _, col, row, angle, lo, size in tries:
        placed = PlacedPiece(piece, angle, (margin + col * cell - lo[0], margin + row * cell - lo[1]))
        if _fits_exactly(plate, placed, margin, spacing):
            grow = spacing + 1.5 * cell
            extra = int(math.ceil(grow / cell))
            rows, cols = int(math.ceil(size[1] / cell)) + 2 * extra, int(math.ceil(size[0] / cell)) + 2 * extra
            own = _mask(PlacedPiece(piece, angle, (0.0, 0.0)).polygon(), lo - extra * cell, rows, cols, cell, grow)
            return placed, own, (row - extra, col - extra)
    return None


def _fits_exactly(plate: Plate, placed: PlacedPiece, margin: float, spacing: float) -> bool:
    from shapely.geometry import box

    polygon = placed.polygon()
    inner = box(margin, margin, plate.size[0] - margin, plate.size[1] - margin)
    if not inner.buffer(1e-9 * plate.size[0]).contains(polygon.buffer(_pad_of(placed), quad_segs=2)):
        return False
    for other in plate.pieces:
        need = spacing + _pad_of(placed) + _pad_of(other)
        shape = other.polygon()
        if _bounds_gap(polygon, shape) < need and polygon.distance(shape) < need:
            return False
    return True


def _bounds_gap(a, b) -> float:
    """The distance between two shapes' bounding boxes: a lower bound of theirs."""
    (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = a.bounds, b.bounds
    return math.hypot(max(bx0 - ax1, ax0 - bx1, 0.0), max(by0 - ay1, ay0 - by1, 0.0))


def _pad_of(placed: PlacedPiece) -> float:
    pattern = placed.piece.pattern
    return _arc_pad(pattern.outline) if pattern.hole is not None or pattern.sector is not None else 0.0


def _top(placed: PlacedPiece) -> float:
    """The highest y of a placed piece, its exact arcs' bulge included."""
    return float(placed.outline[:, 1].max()) + _pad_of(placed)


def check_nesting(plates: list[Plate], fab: Fabrication) -> dict:
    """What the plates hold, measured with shapely on the placed outlines: every piece a
    valid polygon inside its plate at least a kerf from the edge, no two closer than 2 kerf
    (the smallest distances found are reported), and the utilisation: the pieces' area over
    the material the nest uses (each plate's used strip, :attr:`Plate.used_size`; the rest of
    its width is an offcut back to stock), and over the whole plates (``plate_utilisation``)."""
    from shapely.geometry import box

    smallest_gap, smallest_margin, valid = math.inf, math.inf, True
    for plate in plates:
        sheet = box(0.0, 0.0, *plate.size)
        polygons = [p.polygon() for p in plate.pieces]
        for i, polygon in enumerate(polygons):
            valid &= polygon.is_valid and sheet.contains(polygon)
            smallest_margin = min(smallest_margin, sheet.exterior.distance(polygon))
            for other in polygons[i + 1 :]:
                if _bounds_gap(polygon, other) < smallest_gap:  # else it cannot be the smallest
                    smallest_gap = min(smallest_gap, polygon.distance(other))
    area = sum(plate.area for plate in plates)
    used = sum(plate.used_size[0] * plate.used_size[1] for plate in plates)
    tol = 1e-9 * max(fab.plate_size)
    return {
        "plates": len(plates),
        "pieces": sum(len(p.pieces) for p in plates),
        "valid": bool(valid and smallest_gap >= 2 * fab.kerf - tol and smallest_margin >= fab.kerf - tol),
        "smallest_gap": None if math.isinf(smallest_gap) else smallest_gap,
        "smallest_margin": None if math.isinf(smallest_margin) else smallest_margin,
        "utilisation": area / used if used > 0.0 else 0.0,
        "plate_utilisation": area / (len(plates) * plate_area(fab)) if plates else 0.0,
        "per_plate": [
            {
                "plate": p.name,
                "pieces": [q.piece.name for q in p.pieces],
                "used_size": list(p.used_size),
                "utilisation": p.utilisation,
                "plate_utilisation": p.plate_utilisation,
            }
            for p in plates
        ],
    }


def plate_area(fab: Fabrication) -> float:
    return fab.plate_size[0] * fab.plate_size[1]
