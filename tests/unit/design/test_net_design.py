"""A face's net as a design and as a build123d part (issue 44): its wall, its webs, its
names, its refusals, against closed forms.

- The wall of thickness t on one side of the face (offsets w from d_in to d_out along the
  normal) has the volume of Steiner's formula, Int Int (1 - 2 H w + K w^2) dw dA =
  t A - (d_out^2 - d_in^2) Int H dA + (d_out^3 - d_in^3) / 3 Int K dA; on the dome (an
  ellipse of revolution x = a cos t, z = b sin t, a = 500, b = 250) k_meridian = a b / q^3 and
  k_parallel = b / (a q), q = sqrt(a^2 sin^2 t + b^2 cos^2 t), integrated over t by
  Gauss-Legendre.
- A web on a line of curvature is developable, its sides symmetric about it: its volume is
  its development's area times its thickness.
- A parallel of the dome is a circle: its web is a band of a cone, developing to an annular
  sector of radii the cone's slant lengths.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ROOT

from tubecad.core.errors import ParameterError

A, B = 500.0, 250.0  # the dome's semi-axes (tests/shared/host_faces.py)


@pytest.fixture(scope="module")
def dome_face():
    from tubecad.export.cad import read_faces
    from tubecad.occ_compat import as_face

    return as_face(read_faces(ROOT / "samples" / "dome.step")[0][1])


def _dome_integrals(opening: float) -> tuple[float, float, float]:
    """(A, Int H dA, Int K dA) of the elliptical head from the crown opening's radius to the
    equator, in closed form per point, integrated over the ellipse's angle t (x = a cos t,
    z = b sin t) by Gauss-Legendre; H, K for the outward normal (both curvatures bend away from
    it: negative)."""
    t0 = np.arccos(opening / A)
    nodes, weights = np.polynomial.legendre.leggauss(200)
    t = 0.5 * t0 * (nodes + 1.0)
    w = 0.5 * t0 * weights
    x, speed = A * np.cos(t), np.hypot(A * np.sin(t), B * np.cos(t))
    k_meridian = A * B / speed**3
    k_parallel = B / (A * speed)  # the normal's radial part over the radius: (b cos t / speed) / (a cos t)
    area = np.sum(w * 2 * np.pi * x * speed)
    h = -0.5 * (k_meridian + k_parallel)
    k = k_meridian * k_parallel
    return float(area), float(np.sum(w * 2 * np.pi * x * speed * h)), float(np.sum(w * 2 * np.pi * x * speed * k))


@pytest.mark.slow
@pytest.mark.parametrize(("side", "offsets"), [("inside", (-8.0, 0.0)), ("outside", (0.0, 8.0))])
def test_the_walls_volume_is_steiners_formula(dome_face, side, offsets):
    from tubecad.brep import properties as props
    from tubecad.design.model import WallChoice
    from tubecad.design.net import NetDesign

    result = NetDesign(dome_face, 3, 4, wall=WallChoice(8.0, side)).build()
    area, h, k = _dome_integrals(100.0)
    d_in, d_out = offsets
    exact = 8.0 * area - (d_out**2 - d_in**2) * h + (d_out**3 - d_in**3) / 3 * k
    assert props.area(result.design.net.patches) == pytest.approx(area, rel=1e-9)
    assert result.report["brep"]["volume"] == pytest.approx(exact, rel=1e-8)  # measured 4.1e-9 inside, 8.8e-10 outside
    assert result.report["brep"]["valid"] and result.report["brep"]["patches"] == (3 + 1) * 4  # bands x meridians


@pytest.mark.slow
def test_a_parallels_web_is_a_cones_band_developed_exactly(dome_face):
    """The web on a parallel (inside, on the face) is the band of the cone of the normals
    along it: apex on the axis at the normal's crossing, slant R2 = x / cos(normal's angle)
    from the axis to the line; it develops to the annular sector of radii R2 - h .. R2 (inside:
    towards the apex) and angle 2 pi x / R2."""
    from tubecad.design.net import NetDesign, NetStiffenerChoice
    from tubecad.stiffeners.profiles import Profile

    design = NetDesign(dome_face, 3, 4, webs=NetStiffenerChoice(Profile("flat", 60.0, 8.0), k1=(1,), side="inside"))
    result = design.build()
    (web,) = result.webs
    line = design.net.lines["k1_01"]
    x = float(np.hypot(*line.points[0, :2]))
    t = np.arccos(x / A)
    slant = x * np.hypot(A * np.sin(t), B * np.cos(t)) / (B * np.cos(t))  # R2: to the axis along the normal
    angle = 2 * np.pi * x / slant
    exact = 0.5 * angle * (slant**2 - (slant - 60.0) ** 2)
    assert web.pattern.base_length == pytest.approx(2 * np.pi * x, rel=1e-13)  # measured 3.6e-15
    assert web.pattern.area == pytest.approx(exact, rel=1e-13)  # measured 4.1e-15
    # the solid (its curves interpolated through the line's points): measured 1.1e-9
    assert result.report["stiffeners"]["stiffener_k1_01"]["volume"] == pytest.approx(8.0 * exact, rel=1e-8)


@pytest.mark.parametrize("kind", ["T", "L"])
@pytest.mark.parametrize("side", ["outside", "inside"])
def test_a_t_or_l_ring_on_a_parallel_is_pappus_solid_and_its_flange_a_cones_band(dome_face, kind, side):
    """A T or L stiffener on a parallel is a solid of revolution: its volume is Pappus',
    2 pi rho_c A of its cross-section in the meridian plane (the profile's outline put at
    X + w n + s b, n = (b cos t, a sin t) / q the ellipse's outward normal, b = T x n along the
    meridian). Its flange lies on the tangent cone of the offset parallel at the flange's
    mid-thickness: a band of slant radii rho(s) / |b_rho| developing to an annular sector of
    angle 2 pi |b_rho|."""
    from tubecad.design.net import NetDesign, NetStiffenerChoice
    from tubecad.shop.flanges import flange_widths
    from tubecad.shop.net_shop import flange_pattern
    from tubecad.stiffeners.profiles import Profile

    profile = Profile(kind, 60.0, 8.0, 50.0, 6.0)
    design = NetDesign(dome_face, 3, 4, webs=NetStiffenerChoice(profile, k1=(1,), side=side))
    result = design.build()
    line = design.net.lines["k1_01"]
    x, z = float(np.hypot(*line.points[0, :2])), float(line.points[0, 2])
    t = np.arctan2(z / B, x / A)
    q = np.hypot(A * np.sin(t), B * np.cos(t))
    n = np.array([B * np.cos(t), A * np.sin(t)]) / q  # (rho, z), outward
    # T's way round the axis (the traced line's), then b = T x n in the meridian plane
    p0, p1 = line.points[0], line.points[1]
    turning = np.sign(p0[0] * p1[1] - p0[1] * p1[0])  # +1: counter-clockwise about +z
    b = turning * np.array([n[1], -n[0]])  # at azimuth 0: T = (0, turning, 0), T x n = turning (n_z, 0, -n_rho)
    sign = 1.0 if side == "outside" else -1.0
    corners = np.array([[x, z] + sign * w * n + s * b for s, w in profile.outline()])
    rho, zz = corners[:, 0], corners[:, 1]
    cross = rho * np.roll(zz, -1) - np.roll(rho, -1) * zz
    area = 0.5 * cross.sum()
    centroid = ((rho + np.roll(rho, -1)) * cross).sum() / (6 * area)
    pappus = 2 * np.pi * centroid * abs(area)
    volume = result.report["stiffeners"]["stiffener_k1_01"]["volume"]
    assert volume == pytest.approx(pappus, rel=2e-9)  # measured 8.8e-10 (the corner curves are C2 cubics)
    level = sign * (profile.height - profile.flange_thickness / 2)
    centre = np.array([x, z]) + level * n
    w0, w1 = flange_widths(profile)
    slant = lambda s: (centre[0] + s * b[0]) / abs(b[0])
    exact = 0.5 * 2 * np.pi * abs(b[0]) * abs(slant(w1) ** 2 - slant(w0) ** 2)
    flange = flange_pattern(design.net, "ring", "k1_01", profile, side)
    assert flange.area == pytest.approx(exact, rel=1e-12)  # measured 5.8e-15
    assert flange.centre_length == pytest.approx(2 * np.pi * centre[0], rel=1e-12)


def test_a_seed_off_the_face_and_a_bad_web_choice_are_refused(dome_face):
    from tubecad.design.net import NetDesign, NetStiffenerChoice
    from tubecad.stiffeners.profiles import Profile

    with pytest.raises(ParameterError, match="seed must be a point on the face") as off:
        _ = NetDesign(dome_face, 3, 3, seed=(0.0, 0.0, 0.0)).net  # the axis: no point of the dome
    assert off.value.key == "seed"
    design = NetDesign(dome_face, 3, 3, webs=NetStiffenerChoice(Profile("flat", 60.0, 8.0), k2=(5,)))
    with pytest.raises(ParameterError, match=r"k2 must be indices in \[0, 2\]") as bad:
        design.web_lines()
    assert bad.value.key == "k2"


def test_a_spacing_gives_the_lines_of_its_guide_length(dome_face):
    """k2 (the meridians) spaced 2 pi 500 / 10 along the equator-side parallel through the
    seed... the guide is the k1 line (a parallel) through the parameter centre: its length
    2 pi x over the spacing, rounded."""
    from tubecad.design.net import NetDesign
    from tubecad.nets import HostSurface

    host = HostSurface.of_face(dome_face)
    u0, u1, v0, v1 = host.bounds
    x = float(np.hypot(*host.jet(np.array([0.5 * (u0 + u1)]), np.array([0.5 * (v0 + v1)])).X[0, :2]))
    design = NetDesign(dome_face, 2, None, k2_spacing=2 * np.pi * x / 7.2)
    assert design._counts(None) == (2, 7)


@pytest.mark.slow
def test_the_part_places_its_lines_with_its_solids(dome_face):
    import build123d as bd

    from tubecad.parts.net import CurvatureNet

    net = CurvatureNet(bd.Face(dome_face), 3, 4, thickness=8.0, side="inside")
    assert [e.label for e in net.k1] == ["k1_00", "k1_01", "k1_02"]
    for edge in net.k1:  # parallels: one height
        z = [edge.position_at(t).Z for t in np.linspace(0, 1, 9)]
        assert np.ptp(z) < 1e-9
    moved = bd.Pos(0, 0, 100) * net
    assert moved.k1[0].position_at(0.5).Z == pytest.approx(net.k1[0].position_at(0.5).Z + 100.0, abs=1e-9)
    with bd.BuildPart() as part:
        with bd.Locations((2000, 0, 0), (0, 2000, 0)):
            placed = CurvatureNet(bd.Face(dome_face), 3, 4, thickness=8.0, side="inside")
    assert len(part.part.solids()) == 2 and len(placed.k1) == 6
    assert part.part.volume == pytest.approx(2 * net.volume, rel=1e-9)


def test_the_shipped_host_faces_are_the_generators():
    """samples/*.step hold the surfaces tests/shared/host_faces.py makes (their poles)."""
    from OCP.BRep import BRep_Tool
    from shared.host_faces import faces

    from tubecad.export.cad import read_faces
    from tubecad.occ_compat import as_face

    for name, face in faces().items():
        ((_, shipped),) = read_faces(ROOT / "samples" / name)
        ours, theirs = BRep_Tool.Surface_s(face.wrapped), BRep_Tool.Surface_s(as_face(shipped))
        if hasattr(ours, "NbUPoles"):
            a = np.array(
                [
                    [ours.Pole(i, j).XYZ().Coord() for j in range(1, ours.NbVPoles() + 1)]
                    for i in range(1, ours.NbUPoles() + 1)
                ]
            )
            b = np.array(
                [
                    [theirs.Pole(i, j).XYZ().Coord() for j in range(1, theirs.NbVPoles() + 1)]
                    for i in range(1, theirs.NbUPoles() + 1)
                ]
            )
            assert np.abs(a - b).max() < 1e-9
        else:  # the dome: a surface of revolution, compared on points
            for u, v in ((0.3, 0.2), (2.0, 1.0), (5.0, 0.7)):
                assert ours.Value(u, v).Distance(theirs.Value(u, v)) < 1e-9


@pytest.mark.parametrize(
    ("arguments", "key", "says"),
    [
        ({"thickness": -1.0}, "thickness", "thickness"),
        ({"thickness": 2.0, "side": "middle"}, "side", "side must be one of"),
        ({"thickness": 2.0, "stiffened": {"K1": [0]}}, "stiffened", "k1 and k2"),
        ({"thickness": 2.0, "stiffened": {"k1": "some"}}, "stiffened", '"all" or line indices'),
        ({"thickness": 2.0, "stiffened": {"k1": [0]}}, "profile", "profile"),
        ({"thickness": 2.0, "seed": (1.0, 2.0)}, "seed", "(x, y, z)"),
    ],
)
def test_the_parts_arguments_are_refused_naming_them(dome_face, arguments, key, says):
    """Checked once for the build123d part and the CadQuery plugin, before anything is traced."""
    from tubecad.parts.net_arguments import net_part_design

    with pytest.raises(ParameterError, match=r".*") as refused:
        net_part_design(dome_face, 3, 3, **arguments)
    assert refused.value.key == key and says in str(refused.value)
