"""Panels of a canal surface's wall (tubecad.stiffeners.canal_panels)."""

from __future__ import annotations

import math

import pytest
from OCP.TopAbs import TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer

from tubecad.brep import NetLayout, build_wall_solid
from tubecad.brep import properties as props
from tubecad.curves.natural import NaturalAxis
from tubecad.spec.parse import load_spec
from tubecad.stiffeners.panels import split_into_panels
from tubecad.surface import tube_or_canal

SAMPLES = ("nozzle", "tapered_helix", "dupin_cyclide")


@pytest.fixture(scope="module", params=SAMPLES)
def sample_wall(request):
    spec = load_spec(f"samples/{request.param}.toml")
    canal = spec.tube
    build = build_wall_solid(canal, spec.sections["wall"]["thickness"], "centered", NetLayout.equal(canal, 5, 8))
    return request.param, build


def checked(panels, analyzed=(0, -1)):
    """Every panel valid, closed and positive; the panels at ``analyzed`` (indices, or all)
    pass OCCT's pre-boolean check too (seconds per panel: not every one of every split)."""
    for k, p in enumerate(panels):
        assert props.is_valid(p.solid), p.name
        if analyzed == "all" or k in analyzed or k - len(panels) in analyzed:
            assert props.analyzer_findings(p.solid) == {}, p.name
        assert props.free_edges(p.solid) == 0, p.name
        assert props.volume(p.solid) > 0, p.name
    return panels


@pytest.mark.slow
@pytest.mark.parametrize(
    "seams, rings, analyzed",
    [([5, 0, 3], [0, 2, 4], ()), ([2, 6], None, ()), ([1, 2, 3, 4, 5, 6, 7, 0], None, (0, 13, -1))],
)
def test_canal_panels_fit_together_into_the_wall(sample_wall, seams, rings, analyzed):
    name, build = sample_wall
    panels = checked(split_into_panels(build, seams, rings), analyzed)
    n_r = len(rings) - 1 if rings else 4
    assert [p.name for p in panels] == [f"panel_r{i}_s{j}" for i in range(n_r) for j in range(len(set(seams)))]
    wall = props.volume(build.shape)
    assert sum(props.volume(p.solid) for p in panels) == pytest.approx(wall, rel=1e-12)
    # the outer faces are the wall's own outer faces
    assert sum(p.outer_area for p in panels) == pytest.approx(props.faces_area(build.patches[0].all_faces()), rel=1e-12)
    angles = sorted(build.layout.stringers_deg[j] for j in set(seams))
    assert [p.angles_deg for p in panels[: len(angles)]] == list(zip(angles, angles[1:] + [angles[0] + 360.0]))
    assert props.is_valid(build.shape)  # the wall, whose faces and edges the panels share, is left valid


@pytest.mark.slow
def test_canal_one_seam_panels_are_the_ring_bays(sample_wall):
    name, build = sample_wall
    panels = checked(split_into_panels(build, [3], [0, 1, 3, 4]), (0,))
    assert [p.name for p in panels] == ["panel_r0_s0", "panel_r1_s0", "panel_r2_s0"]
    assert [p.angles_deg for p in panels] == [(135.0, 495.0)] * 3
    s = build.layout.s_rings
    assert [p.s_range for p in panels] == [(s[0], s[1]), (s[1], s[3]), (s[3], s[4])]
    assert sum(props.volume(p.solid) for p in panels) == pytest.approx(props.volume(build.shape), rel=1e-12)
    assert sum(p.outer_area for p in panels) == pytest.approx(props.faces_area(build.patches[0].all_faces()), rel=1e-12)


def frustum(r0: float, slope: float, sa: float, sb: float, d_in: float, d_out: float) -> tuple[float, float]:
    """The volume (Pappus) and outer area of the ring bay [sa, sb] of the wall between the
    cones r0 + slope s + d_in and + d_out on a straight axis: the meridian section's corner
    (s, d) lies at z = s - (r + d) r', rho = (r + d) q, q = sqrt(1 - r'^2), its sides straight."""
    q = math.sqrt(1.0 - slope * slope)
    corners = []
    for s, d in ((sa, d_in), (sb, d_in), (sb, d_out), (sa, d_out)):
        radius = r0 + slope * s + d
        corners.append((radius * q, s - radius * slope))
    moment = sum((x0 + x1) * (x0 * y1 - x1 * y0) for (x0, y0), (x1, y1) in zip(corners, corners[1:] + corners[:1])) / 6
    rho_a, rho_b = corners[3][0], corners[2][0]
    return 2.0 * math.pi * abs(moment), math.pi * (rho_a + rho_b) * q * (sb - sa)


@pytest.mark.slow
@pytest.mark.parametrize("r0, slope", [(40.0, -0.1), (10.0, 0.3)])
def test_canal_panels_on_a_cone_are_solids_of_revolution(r0, slope):
    canal = tube_or_canal(NaturalAxis("0", "0", (0.0, 200.0)), f"{r0} + {slope} * s")
    build = build_wall_solid(canal, 2.0, "centered", NetLayout.equal(canal, 5, 4))
    one = checked(split_into_panels(build, [1], [0, 1, 4]), (0,))
    four = checked(split_into_panels(build, [0, 1, 2, 3], [0, 1, 4]), (0, -1))
    for p in one:
        volume, area = frustum(r0, slope, *p.s_range, -1.0, 1.0)
        assert props.volume(p.solid) == pytest.approx(volume, rel=1e-12)
        assert p.outer_area == pytest.approx(area, rel=1e-12)
    for p in four:  # a quarter of the bay, by symmetry
        volume, area = frustum(r0, slope, *p.s_range, -1.0, 1.0)
        assert props.volume(p.solid) == pytest.approx(volume / 4, rel=1e-12)
        assert p.outer_area == pytest.approx(area / 4, rel=1e-12)


def test_canal_panels_survive_a_step_round_trip(tmp_path):
    from tubecad.export.cad import import_shape
    from tubecad.export.registry import export_shape
    from tubecad.stiffeners.assembly import named_assembly

    spec = load_spec("samples/nozzle.toml")
    build = build_wall_solid(spec.tube, 2.0, "centered", NetLayout.equal(spec.tube, 3, 4))
    panels = checked(split_into_panels(build, [0, 2]), ())
    path = export_shape(named_assembly(build, [], panels=panels), tmp_path / "panels.step")
    back = import_shape(path)
    explorer, solids = TopExp_Explorer(back, TopAbs_SOLID), []
    while explorer.More():
        solids.append(explorer.Current())
        explorer.Next()
    assert len(solids) == 4
    assert all(props.is_valid(s) for s in solids)
    assert sum(props.volume(s) for s in solids) == pytest.approx(props.volume(build.shape), rel=1e-9)
