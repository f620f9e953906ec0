"""The shop package's pictures (issue 41) on samples/tee.toml and samples/shop_duct.toml: no
label over another on the overview or a plate's preview, only the panels there is something
for, and the webs' utilisation measured over the strip of plate the nest uses."""

from __future__ import annotations

import tomllib

import pytest
from conftest import ROOT
from shapely.geometry import box

from tubecad.export.labels import overlapping_labels
from tubecad.shop.drawings import plate_figure
from tubecad.shop.nesting import OFFCUT_MIN, check_nesting
from tubecad.shop.writer import overview_figure
from tubecad.spec.parse import parse_spec

SAMPLES = ROOT / "samples"


def shop_of(name: str):
    """The sample's shop package, as ``tubecad shop`` computes it (a junction's stiffeners alone)."""
    from tubecad.shop.package import ShopData, add_stiffener_data, shop_data
    from tubecad.spec.model import FabricationSection

    spec = parse_spec(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), name)
    fab = (spec.fabrication or FabricationSection()).settings(spec.length_unit)
    if spec.branches:
        from tubecad.spec.junction import branch_walls, build_junction_stiffeners

        data = ShopData(None, build_junction_stiffeners(spec, branch_walls(spec)), [], fab)
        add_stiffener_data(data, tuple(spec.layout.net(spec.tube).stringers_deg), spec.fit.tolerance, lambda _: None)
        return data
    from tubecad.spec.build import build_from_spec, panels_from_spec, stiffeners_from_spec

    build = build_from_spec(spec)
    stiffeners, _ = stiffeners_from_spec(spec, build)
    return shop_data(build, stiffeners, panels_from_spec(spec, build), fab)


@pytest.fixture(scope="module")
def tee():
    return shop_of("tee")


@pytest.fixture(scope="module")
def duct():
    return shop_of("shop_duct")


@pytest.mark.slow
@pytest.mark.parametrize("sample", ["tee", "duct"])
def test_no_label_overlaps_another(sample, request):
    data = request.getfixturevalue(sample)
    assert overlapping_labels(overview_figure(data, sample)) == []
    for plate in data.web_plates + data.flange_plates:
        assert overlapping_labels(plate_figure(plate, data.fab)) == [], plate.name


@pytest.mark.slow
def test_the_tee_overview_lays_out_only_what_exists(tee):
    """A junction has no panels: the page holds the webs' plate and a bending table, and says why."""
    fig = overview_figure(tee, "tee")
    titles = sorted(ax.get_title().split(":")[0] for ax in fig.axes)
    assert len(fig.axes) == 2 and titles[0].startswith("bending table") and titles[1] == "webs"
    assert "no panel developments or pin jigs: a junction has no panels yet" in fig.get_suptitle()
    names = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert names == {p.piece.name for p in tee.web_plates[0].pieces}  # every piece on the plate named, once


@pytest.mark.slow
def test_the_duct_overview_shows_development_pin_jig_and_bending(duct):
    fig = overview_figure(duct, "shop_duct")
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert len(titles) == 4 and titles[-1].startswith("webs: plate_01 of 3")
    assert any(t.startswith("panel_") and "developed" in t for t in titles)
    assert any("pin jig" in t for t in titles) and any(t.startswith("bending table") for t in titles)


@pytest.mark.slow
def test_the_tee_webs_utilisation_is_measured_over_the_strip_the_nest_uses(tee):
    """The tee's 16 small webs (flat bar 12 high) take the bottom of one 3000 x 1500 plate:
    1.4 % of the plate, but they use a strip of it a kerf above the highest piece, and the
    rest goes back to stock: the utilisation is measured over that strip (shapely bounds)."""
    fab = tee.fab
    (plate,) = tee.web_plates
    report = check_nesting(tee.web_plates, fab)
    area = sum(p.polygon().area for p in plate.pieces)
    top = max(p.polygon().bounds[3] for p in plate.pieces)
    assert report["plate_utilisation"] == pytest.approx(area / (3000.0 * 1500.0), rel=1e-3)
    assert report["plate_utilisation"] < 0.02
    strip = top + fab.kerf  # the sampled outline; a ring's exact arcs bulge up to 2 sagittas more
    assert plate.used_size[0] == 3000.0 and plate.used_size[1] == pytest.approx(strip, abs=0.05)
    assert 1500.0 - plate.used_size[1] >= OFFCUT_MIN * 1500.0  # the rest is an offcut, not scrap
    assert report["utilisation"] == pytest.approx(area / (3000.0 * strip), rel=1e-3)
    assert report["utilisation"] > 4 * report["plate_utilisation"] and report["utilisation"] > 0.05
    used = box(0.0, 0.0, *plate.used_size)
    assert all(used.contains(p.polygon()) for p in plate.pieces)


@pytest.mark.slow
def test_a_nearly_full_plate_counts_whole(duct):
    """The duct's first two plates leave less than OFFCUT_MIN of their width free: scrap, so
    the whole plate is used; the last one's rest is an offcut."""
    first, second, last = duct.web_plates
    for plate in (first, second):
        assert plate.used_size == plate.size and plate.utilisation == plate.plate_utilisation
    assert last.used_size[1] < (1.0 - OFFCUT_MIN) * last.size[1] and last.utilisation > last.plate_utilisation
    report = check_nesting(duct.web_plates, duct.fab)
    used = 2 * 3000.0 * 1500.0 + 3000.0 * last.used_size[1]
    assert report["utilisation"] == pytest.approx(sum(p.area for p in duct.web_plates) / used, rel=1e-12)
