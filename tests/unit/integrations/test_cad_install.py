"""One consistent OCCT under build123d (and CadQuery when installed), and shapes that pass
between them. tubecad runs on both OCCT generations: build123d 0.12 (+ CadQuery 2.8) on
OCP 7.9, build123d 0.13 on OCP 8 (tubecad.occ_compat holds the names that moved)."""

from importlib.metadata import PackageNotFoundError, version

import pytest


def release(dist: str) -> tuple[int, ...]:
    return tuple(int(p) for p in version(dist).split(".")[:3])


def installed(dist: str) -> bool:
    try:
        version(dist)
        return True
    except PackageNotFoundError:
        return False


def test_one_consistent_ocp_under_build123d():
    import OCP

    from tubecad.occ_compat import OCP_GENERATION

    ocp = tuple(int(p) for p in OCP.__version__.split(".")[:3])
    assert ocp[0] == OCP_GENERATION
    # both OCP distributions write the same `OCP` package: every one installed is that release
    for dist in ("cadquery-ocp", "cadquery-ocp-novtk"):
        if installed(dist):
            assert release(dist) == ocp, dist
    # build123d 0.12 sits on OCP 7.9, 0.13 on OCP 8
    assert (ocp[0] == 8) == (release("build123d")[:2] >= (0, 13))
    if installed("cadquery"):
        assert ocp[:2] == (7, 9) and (2, 8) <= release("cadquery")[:2] < (2, 9)


def test_a_build123d_solid_is_used_by_cadquery_and_back():
    import build123d as bd

    cq = pytest.importorskip("cadquery", reason="CadQuery is the extra tubecad[cadquery]")
    box = bd.Box(20, 10, 5) - bd.Cylinder(2, 5)
    workplane = cq.Workplane().add(cq.Shape.cast(box.wrapped)).faces(">Z").workplane().center(6, 0).hole(3)
    cq_solid = workplane.val()
    assert cq_solid.isValid()
    assert cq_solid.Volume() == pytest.approx(1000 - 3.141592653589793 * (4 + 1.5**2) * 5, rel=1e-9)
    back = bd.Solid(cq_solid.wrapped)
    assert back.is_valid and back.volume == pytest.approx(cq_solid.Volume(), rel=1e-12)
    assert len(back.faces()) == len(cq_solid.Faces())


def test_the_cadquery_plugin_says_how_to_install_cadquery_when_missing():
    import importlib
    import sys

    if installed("cadquery"):
        pytest.skip("CadQuery is installed here")
    sys.modules.pop("tubecad.integrations.cadquery_plugin", None)
    with pytest.raises(ImportError, match=r"pip install 'tubecad\[cadquery\]'"):
        importlib.import_module("tubecad.integrations.cadquery_plugin")
