"""Labels that never overlap (issue 41): the check finds overlapping texts in a drawn figure,
and the placer writes crowded names apart, off other pieces, with leaders where it moves them."""

import numpy as np
from matplotlib.figure import Figure

from tubecad.export.labels import drawn_texts, overlapping_labels, place_labels


def test_the_check_finds_overlapping_texts_and_passes_separate_ones():
    fig = Figure(figsize=(4, 3))
    ax = fig.add_axes((0.1, 0.1, 0.8, 0.8))
    ax.set_axis_off()
    ax.text(0.5, 0.5, "stringer_00", ha="center")
    ax.text(0.52, 0.51, "stringer_04", ha="center")  # nearly on top of the first
    ax.text(0.5, 0.1, "ring_01", ha="center")
    assert overlapping_labels(fig) == [("stringer_00", "stringer_04")]
    ax.texts[1].set_position((0.5, 0.8))
    assert overlapping_labels(fig) == []
    assert {t.get_text() for t, _ in drawn_texts(fig)} == {"stringer_00", "stringer_04", "ring_01"}


def test_the_check_sees_titles_ticks_and_legends():
    fig = Figure(figsize=(3, 2))
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], label="a line")
    ax.legend(loc="lower right")
    ax.set_title("a title")
    texts = {t.get_text(): box for t, box in drawn_texts(fig)}
    assert {"a line", "a title", "0.00", "1.00"} <= set(texts)  # tick labels too
    assert overlapping_labels(fig) == []
    title = texts["a title"]
    fig.text(title.x0 / fig.dpi / 3, title.y0 / fig.dpi / 2, "written over it")  # figure fractions
    assert [frozenset(pair) for pair in overlapping_labels(fig)] == [frozenset(("a title", "written over it"))]


def test_crowded_names_are_placed_apart_with_leaders_and_off_other_pieces():
    fig = Figure(figsize=(6, 3), dpi=100)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    ax.set_xlim(0, 100)
    ax.set_ylim(0, 50)
    ax.set_aspect("equal")
    ax.set_axis_off()
    squares = [np.array([[x, 2], [x + 4, 2], [x + 4, 6], [x, 6]]) for x in np.arange(10, 50, 5.0)]  # 8 small parts
    names = [f"stringer_{k:02d}" for k in range(len(squares))]
    anchors = [tuple(sq.mean(axis=0)) for sq in squares]
    moved = place_labels(ax, anchors, names, fontsize=8, outlines=[[sq] for sq in squares])
    assert overlapping_labels(fig) == []
    assert moved >= 4  # names far wider than their parts: most moved off, each with a leader
    assert sum(1 for t in ax.texts if getattr(t, "arrow_patch", None) is not None) == moved
    renderer_boxes = {t.get_text(): b for t, b in drawn_texts(fig)}
    for k, name in enumerate(names):  # no name lies on another part
        box = renderer_boxes[name]
        for j, sq in enumerate(squares):
            if j != k:
                corners = ax.transData.transform(sq)
                lo, hi = corners.min(axis=0), corners.max(axis=0)
                assert not (box.x0 < hi[0] and lo[0] < box.x1 and box.y0 < hi[1] and lo[1] < box.y1), (name, j)
