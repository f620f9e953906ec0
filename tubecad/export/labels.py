"""Labels that do not overlap: names placed in a matplotlib Axes with a check, and the check
of a whole figure.

:func:`place_labels` puts each name at its anchor if its box there meets no label placed
before it, no outline it must keep off and stays inside the axes; else at the nearest free
spot on rings round the anchor, with a thin leader line back to it; else a size smaller,
down to a floor. :func:`overlapping_labels` draws a figure (Agg, off screen) and returns
every pair of drawn texts whose boxes intersect: titles, axis labels, tick labels, legend
entries and placed labels alike. Both measure text as the Agg renderer draws it, at the
figure's own dpi: the layout must be final (no ``tight_layout`` afterwards).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.backends.backend_agg import RendererAgg
from matplotlib.path import Path as MplPath
from matplotlib.text import Text
from matplotlib.transforms import Bbox

#: candidate spots: this many directions round the anchor ...
DIRECTIONS = 16
#: ... on rings this many text heights apart ...
RING_STEP = 1.1
#: ... out to this many rings
MAX_RINGS = 40
#: each failed round shrinks the text by this factor
SHRINK = 0.85
#: boxes closer than this (pixels) count as touching
GAP_PX = 1.0


def renderer_of(fig) -> RendererAgg:
    """An off-screen Agg renderer of ``fig``'s size and dpi, with the figure drawn once into it
    (so that aspect ratios and layouts are applied before anything is measured)."""
    width, height = fig.get_size_inches() * fig.dpi
    renderer = RendererAgg(int(math.ceil(width)), int(math.ceil(height)), fig.dpi)
    fig.draw(renderer)
    return renderer


def drawn_texts(fig) -> list[tuple[Text, Bbox]]:
    """Every text ``fig`` draws, with its box in pixels.

    Args:
        fig: a matplotlib Figure.

    Returns:
        (text artist, window extent) of each visible, non-blank text drawn: titles, axis and
        tick labels, legend entries, annotations, colour-bar labels.
    """
    drawn: list[tuple[Text, Bbox]] = []
    original = Text.draw

    def spy(self: Text, renderer) -> None:
        original(self, renderer)
        if self.get_visible() and self.get_text().strip():
            drawn.append((self, Text.get_window_extent(self, renderer)))  # an annotation's text, not its arrow

    Text.draw = spy  # type: ignore[method-assign,assignment]  # only while this figure is drawn
    try:
        renderer_of(fig)
    finally:
        Text.draw = original  # type: ignore[method-assign]
    return drawn


def overlapping_labels(fig, gap_px: float = 0.0) -> list[tuple[str, str]]:
    """The pairs of drawn texts of ``fig`` whose boxes intersect.

    Args:
        fig: a matplotlib Figure, its layout final.
        gap_px: boxes closer than this count as overlapping too.

    Returns:
        (text, text) of each overlapping pair; empty when every label reads clear.
    """
    boxes = [(t.get_text(), b) for t, b in drawn_texts(fig)]
    return [
        (a, b)
        for i, (a, box_a) in enumerate(boxes)
        for b, box_b in boxes[i + 1 :]
        if _overlap(np.asarray(box_a.extents), np.asarray(box_b.extents), gap_px)
    ]


def place_labels(
    ax,
    anchors: Sequence[tuple[float, float]],
    names: Sequence[str],
    *,
    fontsize: float = 7.0,
    min_fontsize: float = 4.5,
    outlines: Sequence[Sequence[np.ndarray]] = (),
    colour: str = "#10203a",
) -> int:
    """Write ``names`` at ``anchors`` (data coordinates) in ``ax`` so that no two overlap.

    Args:
        ax: the Axes, in a figure whose layout is final.
        anchors: each label's point, e.g. a point inside its piece.
        names: the labels.
        fontsize: the labels' size (points), shrunk by SHRINK while no free spot is found.
        min_fontsize: the smallest size tried; a label with no free spot even then is written
            at its anchor at this size.
        outlines: per label, the closed outlines (data coordinates) of its own piece; a label
            keeps off other pieces and, where it can, off its own piece's outlines (it may lie on
            its own piece's material).
        colour: the text and leader colour.

    Returns:
        How many labels were moved off their anchors (each with a leader line).
    """
    renderer = renderer_of(ax.figure)
    frame = ax.get_window_extent(renderer).extents
    taken: list[np.ndarray] = [
        np.asarray(Text.get_window_extent(t, renderer).extents) for t in ax.texts if t.get_visible() and t.get_text()
    ]
    pieces = [_Piece([ax.transData.transform_path(MplPath(np.asarray(o))) for o in own]) for own in outlines]
    anchored = ax.transData.transform(np.asarray(anchors, dtype=float).reshape(-1, 2))
    moved = 0
    for k, (name, at) in enumerate(zip(names, anchored)):
        size, spot = fontsize, None
        others = [piece for j, piece in enumerate(pieces) if j != k]
        own = pieces[k : k + 1]
        while spot is None:
            w, h = _text_size(ax, name, size, renderer)
            spot = _free_spot(at, w, h, frame, taken, others, own)  # clear of its own outlines too
            if spot is None:
                spot = _free_spot(at, w, h, frame, taken, others, [])
            if spot is None and size * SHRINK < min_fontsize:
                spot = at
            elif spot is None:
                size *= SHRINK
        taken.append(np.array([spot[0] - w / 2, spot[1] - h / 2, spot[0] + w / 2, spot[1] + h / 2]))
        moved += _write(ax, name, at, spot, size, h, colour)
    return moved


def _write(ax, name: str, at: np.ndarray, spot: np.ndarray, size: float, h: float, colour: str) -> int:
    """Write ``name`` centred on the pixel ``spot``; a leader line to ``at`` if it moved.
    Returns 1 if it moved, else 0."""
    xy, xytext = ax.transData.inverted().transform(np.array([at, spot]))
    if np.hypot(*(spot - at)) < 0.5 * h:
        ax.text(*xytext, name, fontsize=size, ha="center", va="center", color=colour)
        return 0
    ax.annotate(
        name,
        xy=tuple(xy),
        xytext=tuple(xytext),
        fontsize=size,
        ha="center",
        va="center",
        color=colour,
        arrowprops={"arrowstyle": "-", "color": colour, "lw": 0.5, "alpha": 0.7, "shrinkA": 0, "shrinkB": 1},
    )
    return 1


def _text_size(ax, name: str, size: float, renderer) -> tuple[float, float]:
    """(width, height) in pixels of ``name`` at ``size`` points, as Agg draws it."""
    probe = ax.text(0.0, 0.0, name, fontsize=size, ha="center", va="center")
    box = probe.get_window_extent(renderer)
    probe.remove()
    return box.width, box.height


class _Piece:
    """A piece's outlines in pixels (its outer outline, then any holes), with their box."""

    def __init__(self, paths: list[MplPath]):
        self.paths = paths
        corners = np.concatenate([p.vertices for p in paths]) if paths else np.zeros((1, 2))
        self.extents = np.concatenate([corners.min(axis=0), corners.max(axis=0)])

    def crosses(self, box: np.ndarray) -> bool:
        """Whether a label's box (x0, y0, x1, y1) crosses one of the outlines."""
        if not _overlap(box, self.extents, 0.0):
            return False
        bbox = Bbox.from_extents(*box)
        return any(p.intersects_bbox(bbox, filled=False) for p in self.paths)

    def blocks(self, box: np.ndarray) -> bool:
        """Whether a label's box (x0, y0, x1, y1) crosses an outline or lies in the material."""
        if not _overlap(box, self.extents, 0.0):
            return False
        if self.crosses(box):
            return True
        centre = (0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3]))
        return sum(p.contains_point(centre) for p in self.paths) % 2 == 1  # inside the outline, not in a hole


def _free_spot(
    at: np.ndarray,
    w: float,
    h: float,
    frame: np.ndarray,
    taken: list[np.ndarray],
    others: list[_Piece],
    own: list[_Piece],
) -> np.ndarray | None:
    """The first spot (pixels) on rings round ``at`` where a w x h box stays inside ``frame``,
    meets no box of ``taken``, no piece of ``others`` and crosses no outline of ``own``
    (it may lie on its own piece); None if there is none."""
    angles = np.radians(np.arange(DIRECTIONS) * 360.0 / DIRECTIONS + 90.0)  # up first, then round
    for ring in range(MAX_RINGS + 1):
        radius = ring * RING_STEP * h
        for angle in angles[: 1 if ring == 0 else DIRECTIONS]:
            spot = at + radius * np.array([math.cos(angle), math.sin(angle)])
            box = np.array([spot[0] - w / 2, spot[1] - h / 2, spot[0] + w / 2, spot[1] + h / 2])
            if not _inside(box, frame) or any(_overlap(box, t, GAP_PX) for t in taken):
                continue
            if not any(piece.blocks(box) for piece in others) and not any(piece.crosses(box) for piece in own):
                return spot
    return None


def _inside(box: np.ndarray, frame: np.ndarray) -> bool:
    return bool(box[0] >= frame[0] and box[1] >= frame[1] and box[2] <= frame[2] and box[3] <= frame[3])


def _overlap(a: np.ndarray, b: np.ndarray, gap: float) -> bool:
    """Whether boxes (x0, y0, x1, y1) come closer than ``gap`` (intersect, for 0)."""
    return bool(a[0] < b[2] + gap and b[0] < a[2] + gap and a[1] < b[3] + gap and b[1] < a[3] + gap)
