"""The projections of a built tube (issue 41): titled with the net as built, the surface
sampled finely whatever the net, the net's hidden halves found, and no label over another."""

import math
import tomllib

import numpy as np
import pytest

from tubecad.export.labels import overlapping_labels
from tubecad.export.plots import U_SAMPLES, projection_figure, projection_figure_of_build
from tubecad.spec.build import build_from_spec
from tubecad.spec.paper import paper_tube
from tubecad.spec.parse import parse_spec

HELIX = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 900.0]

[tube]
radius = 12.0

[layout]
rings = 7
stringers = 6
"""


@pytest.fixture(scope="module")
def helix():
    """A helical tube (three turns' worth of one coil) built on 7 rings x 6 stringers, and its projections."""
    build = build_from_spec(parse_spec(tomllib.loads(HELIX), "helix"))
    return build, projection_figure_of_build(build)


def collections(fig, gid: str) -> list:
    return [c for ax in fig.axes for c in ax.collections if c.get_gid() == gid]


def test_the_title_states_the_net_as_built(helix):
    build, fig = helix
    rings, stringers = len(build.ring_wires()), len(build.stringer_wires())  # the solid's own edges
    assert (rings, stringers) == (7, 6)
    title = fig.get_suptitle()
    assert f"{rings} rings x {stringers} stringers" in title
    assert "rho = 12" in title and f"fit tolerance {build.tolerance:g}" in title
    legend = {t.get_text() for t in fig.legends[0].get_texts()}
    assert f"{rings} ring frames (s = const)" in legend and f"{stringers} stringers (u = const)" in legend


def test_no_label_overlaps_another(helix):
    _, fig = helix
    assert overlapping_labels(fig) == []


def test_the_far_half_of_each_ring_is_hidden(helix):
    """Seen from the side, a ring frame shows about half of itself; the rest is drawn faint."""
    _, fig = helix
    frontal = fig.axes[0]

    def length(gid: str) -> float:  # of the polylines drawn, on the screen
        lines = [line for c in frontal.collections if c.get_gid() == gid for line in c.get_segments()]
        return sum(float(np.linalg.norm(np.diff(line, axis=0), axis=1).sum()) for line in lines)

    visible, hidden = length("rings visible"), length("rings hidden")
    assert 0.35 < visible / (visible + hidden) < 0.65


def test_the_surface_is_drawn_finely_whatever_the_net():
    """A net of 3 rings x 2 stringers on the paper's tube still gets a fine surface: at least
    U_SAMPLES round and a sample every 0.03 rad of the axis' turning along it."""
    tube = paper_tube()
    fig = projection_figure(tube, rings=3, stringers=2)
    (surface, *_) = collections(fig, "surface")
    turning = 10.0 * math.log(1200.0 / 200.0)  # k = a / s, a = 10: the axis turns by a ln(s1 / s0)
    assert len(surface.get_paths()) >= 2 * U_SAMPLES * turning / 0.03  # two triangles per cell
    title = fig.get_suptitle()
    assert "3 rings x 2 stringers" in title
