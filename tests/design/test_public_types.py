"""The public names resolve for type checkers (issue 42): ``tubecad/__init__.py`` imports its
names lazily (PEP 562), so a ``TYPE_CHECKING`` block names each one's own type; without it
``from tubecad import CurvatureWall`` was ``Any`` to mypy and to IDEs."""

from __future__ import annotations

import ast
import subprocess
import sys

import pytest
from conftest import ROOT

import tubecad

INIT = ROOT / "tubecad" / "__init__.py"


def type_checking_imports() -> dict[str, str]:
    """name -> module, as imported inside ``if TYPE_CHECKING:`` in tubecad/__init__.py."""
    tree = ast.parse(INIT.read_text())
    block = next(n for n in tree.body if isinstance(n, ast.If) and getattr(n.test, "id", "") == "TYPE_CHECKING")
    return {
        alias.asname or alias.name: node.module
        for node in block.body
        if isinstance(node, ast.ImportFrom) and node.module
        for alias in node.names
    }


def test_every_public_name_has_its_type_for_type_checkers():
    """The same names, from the same modules, as the lazy table (``_PUBLIC``) and the moved
    names (``_MOVED``) import at run time."""
    assert type_checking_imports() == {**tubecad._PUBLIC, **tubecad._MOVED}


def test_the_top_level_is_curated_and_a_moved_name_says_where_it_went():
    """``__all__`` holds the parts, axes, laws, layouts, profiles, specs, export and errors, not
    the junction internals nor the paper's demo tube; those still import, with a warning
    naming their package, and are the same objects."""
    import tubecad.junctions
    import tubecad.spec.paper

    assert not set(tubecad._MOVED) & set(tubecad.__all__)
    for name in (
        "CurvatureWall",
        "CurvatureJunction",
        "Helix",
        "RadiusLaw",
        "NetLayout",
        "Profile",
        "load_spec",
        "build_spec",
        "export_shape",
        "SpecError",
        "AxisLike",
        "RadiusLike",
        "WallSide",
    ):
        assert name in tubecad.__all__, name
    with pytest.warns(DeprecationWarning, match=r"tubecad.saddle_curve moved: import it from tubecad.junctions"):
        assert tubecad.saddle_curve is tubecad.junctions.saddle_curve
    with pytest.warns(DeprecationWarning, match=r"from tubecad.spec.paper"):
        assert tubecad.paper_tube is tubecad.spec.paper.paper_tube
    with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
        tubecad.no_such_name  # noqa: B018 - the attribute access is the test


@pytest.mark.slow
def test_mypy_sees_the_classes_and_their_typed_arguments(tmp_path):
    """mypy on a user's script: the parts are their classes, with the axis, radius and wall
    side typed by the public aliases (measured: ~20 s with a cold cache)."""
    script = tmp_path / "script.py"
    script.write_text(
        "import tubecad\n"
        "reveal_type(tubecad.CurvatureWall)\n"
        "reveal_type(tubecad.Helix)\n"
        "reveal_type(tubecad.NetLayout.equal)\n"
        "tubecad.CurvatureWall([(0, 0, 0), (0, 0, 100)], radius=10, thickness=1, side='astride')\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "cache"), "--follow-imports=silent", str(script)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    revealed = [line.split("Revealed type is ")[1] for line in done.stdout.splitlines() if "Revealed type" in line]
    assert len(revealed) == 3, done.stdout + done.stderr
    assert revealed[0].endswith('-> tubecad.parts.build123d_parts.CurvatureWall"')
    assert "side: Literal['centered'] | Literal['inside'] | Literal['outside']" in revealed[0]
    assert (
        "radius: float | str | typing.Sequence[typing.Sequence[float]] | tubecad.curves.radius_law.RadiusLaw"
        in revealed[0]
    )
    assert revealed[1].endswith('-> tubecad.curves.families.Helix"')
    assert revealed[2].endswith('-> tubecad.brep.layout.NetLayout"')
    # a side no wall has is a type error, named by mypy
    assert 'Argument "side" to "CurvatureWall" has incompatible type "Literal[\'astride\']"' in done.stdout
