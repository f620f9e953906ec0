"""The shaded B-rep picture: a solid read back from STEP renders to a real PNG."""

import matplotlib.image as mpimg
import numpy as np
import pytest

build123d = pytest.importorskip("build123d")

from tubecad.export.render import render_shape_png

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def solid(tmp_path_factory):
    """A box with a through hole, written to STEP and read back."""
    from build123d import Box, Cylinder, export_step, import_step

    step = tmp_path_factory.mktemp("step") / "holed_box.step"
    assert export_step(Box(40, 30, 20) - Cylinder(8, 40), step)
    return import_step(step)


def test_render_writes_a_shaded_picture_with_edges(solid, tmp_path):
    target = tmp_path / "x.png"
    out = render_shape_png(solid.wrapped, target, title="box with a hole", size_px=(800, 600))
    assert out == target
    assert target.read_bytes()[:8] == PNG_MAGIC
    rgb = mpimg.imread(target)[:, :, :3]
    assert rgb.shape[:2] == (600, 800)
    background = np.all(rgb > 0.98, axis=-1)
    assert (~background).mean() > 0.05
    dark = np.all(rgb < 0.25, axis=-1)  # edge colour #10203a and the shadowed faces stay above this
    assert dark.sum() > 200
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.png"]  # no temporary left behind


@pytest.mark.slow
def test_other_view_gives_another_picture(solid, tmp_path):
    a = render_shape_png(solid, tmp_path / "a.png", size_px=(400, 300))  # build123d object is accepted
    b = render_shape_png(solid, tmp_path / "b.png", view_dir=(0.0, 0.0, 1.0), size_px=(400, 300))
    ia, ib = mpimg.imread(a), mpimg.imread(b)
    assert ia.shape == ib.shape
    assert np.abs(ia - ib).mean() > 0.01
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.png", "b.png"]


def test_a_curved_surface_is_shaded_smoothly(tmp_path):
    """Issue 41: a sphere reads round, not faceted. With its edges drawn transparent, the
    luminance's Laplacian is small almost everywhere on it: flat-shaded facets (0.3 rad) put a
    step at every facet border (17 % of the pixels above 0.02), smooth shading on a fine mesh
    keeps them under 2 %."""
    from build123d import Sphere
    from scipy import ndimage

    out = render_shape_png(Sphere(10.0), tmp_path / "sphere.png", size_px=(400, 300), edge_color=(1, 1, 1, 0))
    rgb = mpimg.imread(out)[:, :, :3]
    body = ndimage.binary_erosion(np.any(rgb < 0.97, axis=-1), iterations=4)  # the sphere, off its outline
    assert body.sum() > 40_000
    steps = np.abs(ndimage.laplace(rgb.mean(axis=2)))[body]
    assert (steps > 0.02).mean() < 0.02
