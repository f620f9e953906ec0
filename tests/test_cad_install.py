"""One consistent OCCT under build123d and CadQuery, and shapes that pass between them."""

from importlib.metadata import version

import pytest


def release(dist: str) -> tuple[int, ...]:
    return tuple(int(p) for p in version(dist).split(".")[:3])


def test_one_consistent_ocp_for_build123d_and_cadquery():
    import OCP

    # Both OCP distributions write the same `OCP` package: they must be the same release.
    assert release("cadquery-ocp") == release("cadquery-ocp-novtk")
    assert tuple(int(p) for p in OCP.__version__.split(".")[:3]) == release("cadquery-ocp")
    assert (7, 9, 3) <= release("cadquery-ocp") < (7, 10, 0)
    assert (0, 12) <= release("build123d")[:2] < (0, 13)
    assert (2, 8) <= release("cadquery")[:2] < (2, 9)


def test_a_build123d_solid_is_used_by_cadquery_and_back():
    import build123d as bd
    import cadquery as cq

    box = bd.Box(20, 10, 5) - bd.Cylinder(2, 5)
    workplane = cq.Workplane().add(cq.Shape.cast(box.wrapped)).faces(">Z").workplane().center(6, 0).hole(3)
    cq_solid = workplane.val()
    assert cq_solid.isValid()
    assert cq_solid.Volume() == pytest.approx(1000 - 3.141592653589793 * (4 + 1.5**2) * 5, rel=1e-9)
    back = bd.Solid(cq_solid.wrapped)
    assert back.is_valid and back.volume == pytest.approx(cq_solid.Volume(), rel=1e-12)
    assert len(back.faces()) == len(cq_solid.Faces())
