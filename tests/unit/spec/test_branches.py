"""[[branches]] in a spec (issue 25): each bad value refused in one line naming its key, before
anything is built; the branch placed where its keys say; the commands that would drop the
branches refuse the spec. The commands themselves run in tests/e2e/test_cli_branches.py."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shared.branches import BRANCH, MAIN, spec_text

from tubecad import SpecError
from tubecad.spec.parse import parse_spec


def parsed(text: str):
    import tomllib

    return parse_spec(tomllib.loads(text), "tee.toml")


def test_a_branch_is_placed_where_its_keys_say():
    """The main axis runs along x with r1 = y, r2 = z: angle 60, around 90, offset 10 put the
    branch's axis through (150, -10, 0) along (cos 60, 0, sin 60), its first stringer towards +x."""
    spec = parsed(spec_text(BRANCH + "angle = 60.0\naround = 90.0\noffset = 10.0\n"))
    branch = spec.branches[0].surface(spec.tube)
    a = math.radians(60.0)
    ends = branch.axis.position(np.array([0.0, 150.0]))
    assert np.allclose(ends[0], [150.0, -10.0, 0.0], atol=1e-12)
    assert np.allclose(ends[1] - ends[0], 150.0 * np.array([math.cos(a), 0.0, math.sin(a)]), atol=1e-9)
    t, r1, _ = (v[0] for v in branch.axis.rotation_minimising_frame(np.array([0.0])))
    assert np.allclose(r1, [math.sin(a), 0.0, -math.cos(a)], atol=1e-12) and abs(t @ r1) < 1e-15
    assert branch.radius == 30.0 and spec.branches[0].wall is None  # the main [wall] by default


@pytest.mark.parametrize(
    ("branch", "main", "key", "says"),
    [
        (BRANCH, MAIN.replace("[wall]\nthickness = 4.0\n", ""), "wall", "needs a [wall] section"),
        (BRANCH.replace("at = 150.0", "at = 400.0"), MAIN, "branches.at", "at must be inside the main axis' span"),
        (BRANCH + "angle = 0.0\n", MAIN, "branches.angle", "angle must be in (0, 180)"),
        (BRANCH + "angle = 180.0\n", MAIN, "branches.angle", "angle must be in (0, 180)"),
        (BRANCH.replace("length = 150.0", "length = -1.0"), MAIN, "branches.length", "length must be > 0"),
        # the builder's rule (tubecad.junctions.placement.branch_start_problem): outer in outer, bore in bore
        (
            BRANCH.replace("radius = 30.0", "radius = 50.5"),
            MAIN,
            "branches.radius",
            "the branch's outer surface must start inside the main tube's outer surface: it reaches 52.5",
        ),
        (
            BRANCH.replace("radius = 30.0", "radius = 49.5") + "wall = { thickness = 0.5 }\n",
            MAIN,
            "branches.radius",
            "the branch's bore must start inside the main tube's bore: it reaches 49.25",
        ),
        (BRANCH + "offset = 25.0\n", MAIN, "branches.offset", "must start inside the main tube's outer surface"),
        (BRANCH.replace("radius = 30.0", "radius = 0.0"), MAIN, "branches.radius", "radius"),
        (BRANCH + "flange = 1.0\n", MAIN, "branches", "unknown key [[branches]] #1 flange"),
        (BRANCH + 'axis = { k = "foo(s)" }\n', MAIN, "branches.axis.k", "function 'foo' is not allowed"),
        (BRANCH + 'axis = { tau = "1/0" }\n', MAIN, "branches.axis.tau", "tau(s) is not finite"),
        (BRANCH + 'axis = { q = "1" }\n', MAIN, "branches.axis", "unknown key [[branches]] #1 [axis] q"),
        (BRANCH + "pad = { thickness = 6.0 }\n", MAIN, "branches.pad.width", "width is missing"),
        (BRANCH + "pad = { thickness = -6.0, width = 20.0 }\n", MAIN, "branches.pad.thickness", "must be > 0"),
        (BRANCH + 'wall = { thickness = 3.0, side = "middle" }\n', MAIN, "branches.wall.side", "side must be one of"),
        (BRANCH + "wall = 3.0\n", MAIN, "branches.wall", "must be an inline table"),
        (BRANCH + "layout = { rings = 1 }\n", MAIN, "branches.layout.rings", "rings"),
        (BRANCH.replace("length = 150.0\n", ""), MAIN, "branches.length", "length is missing"),
        (BRANCH, MAIN + "[panels]\nseams = [0, 4]\n", "panels", "not built yet"),
        (BRANCH + "stiffeners = { rings = [1] }\n", MAIN, "stiffeners", "the spec needs a [stiffeners] section"),
        (
            BRANCH + "stiffeners = { rings = [3] }\n",
            MAIN + "[stiffeners]\nrings = [1]\nheight = 3.0\nthickness = 1.0\n",
            "branches.stiffeners.rings",
            "stiffeners.rings must be indices in [0, 2], got [3]",
        ),
        (
            BRANCH + "stiffeners = { stringers = [1], start = -1.0 }\n",
            MAIN + "[stiffeners]\nrings = [1]\nheight = 3.0\nthickness = 1.0\n",
            "branches.stiffeners.start",
            "start must be",
        ),
    ],
)
def test_bad_branches_are_refused_in_one_line_naming_the_key(branch, main, key, says):
    with pytest.raises(SpecError) as info:
        parsed(spec_text(branch, main))
    message = str(info.value)
    assert info.value.key == key and says in message and "\n" not in message, (info.value.key, message)


def test_the_second_branch_is_named_in_the_message():
    with pytest.raises(SpecError, match=r"\[\[branches\]\] #2 .*angle must be in \(0, 180\)"):
        parsed(spec_text(BRANCH + BRANCH.replace("150.0\nlength", "300.0\nlength") + "angle = 200.0\n"))


def test_branches_must_be_tables():
    with pytest.raises(SpecError, match=r"\[\[branches\]\] must be tables") as info:
        parsed("branches = 3\n" + MAIN)
    assert info.value.key == "branches"


def test_the_library_calls_that_make_the_main_tube_alone_refuse_branches():
    """shop, flat and the viewer build through build_from_spec: it refuses rather than drop them."""
    from tubecad.spec.build import build_from_spec

    with pytest.raises(SpecError, match=r"this command does not make junctions yet") as info:
        build_from_spec(parsed(spec_text()))
    assert info.value.key == "branches"


def test_a_bad_branch_is_refused_before_occt_loads(tmp_path):
    """The spec checker places the branch with numpy alone: a mistake costs no OCCT start-up."""
    import subprocess
    import sys

    spec = tmp_path / "tee.toml"
    spec.write_text(spec_text(BRANCH + "angle = 200.0\n"))
    code = (
        "import sys, tomllib\nfrom tubecad.spec.parse import parse_spec\n"
        f"try:\n    parse_spec(tomllib.loads(open({str(spec)!r}).read()))\nexcept Exception as exc:\n    print(exc.key)\n"
        "print(sorted(m for m in ('OCP', 'build123d') if m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["branches.angle", "[]"]


def test_a_curved_branch_follows_its_natural_equations():
    """axis = { k = "1/200" }: the branch leaves (150, 0, 0) up z and bends towards +x on the
    circle of radius 200 in the x-z plane: c(s) = (150 + 200 (1 - cos(s/200)), 0, 200 sin(s/200))."""
    spec = parsed(spec_text(BRANCH + 'axis = { k = "1/200" }\n'))
    s = np.linspace(0.0, 150.0, 7)
    got = spec.branches[0].surface(spec.tube).axis.position(s)
    want = np.column_stack([150 + 200 * (1 - np.cos(s / 200)), np.zeros_like(s), 200 * np.sin(s / 200)])
    assert np.abs(got - want).max() < 1e-9


@pytest.mark.parametrize("radius", [46.5, 48.0, 49.0])
def test_the_spec_takes_the_near_equal_branches_the_builder_builds(radius):
    """Issue 43: one rule for the spec and the builder. With 4 mm walls on R = 50 the old rule
    r + t_b/2 < R - t/2 stopped spec tees at r/R < 0.92; the builder makes r = 49 (one valid
    solid, its saddles 1e-10 from the exact ones: tests/unit/junctions/test_near_equal.py),
    so the spec takes it too."""
    spec = parsed(spec_text(BRANCH.replace("radius = 30.0", f"radius = {radius}")))
    assert spec.branches[0].radius == radius
