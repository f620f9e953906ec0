"""Canal surfaces on closed axes from the command line: a radius law that does not close is
refused in one line, exit 2, no file; samples/saddle_canal_closed.toml builds to STEP; a
stringer that would touch its own start is refused; ring frames all round the closed wall.
"""

import pytest
from click.testing import CliRunner
from conftest import ROOT
from shared.closed_canal import CLOSED_TREFOIL
from shared.closed_tubes import TWO_PI, trefoil

from tubecad.brep import properties as props
from tubecad.cli.app import cli
from tubecad.core.errors import ParameterError
from tubecad.curves.parametric import ParametricAxis
from tubecad.surface import CanalSurface

SAMPLE = ROOT / "samples" / "saddle_canal_closed.toml"
#: every check of OCCT's pre-boolean analyzer but the self-intersection one (minutes on the
#: trefoil's walls; the torus-like wall below gets every check)
CHECKS = tuple(mode for mode in props.ANALYZER_MODES if mode != "SelfInterMode")


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.mark.parametrize(
    "radius, says",
    [
        ('"8 + 0.001 * s"', "[tube] radius: on a closed axis the law must close (r and r' at s = "),
        ('"8 + 0.5 * sin(s / 40)"', "they differ by"),
        ("[[-10.0, 8.0], [300.0, 9.0], [2000.0, 8.0]]", "[tube] radius: on a closed axis the table must run from"),
        (
            "[[0.0, 8.0], [300.0, 9.0], [700.0, 8.5], [1400.0, 8.5]]",
            "[tube] radius: on a closed axis a table must close (row 0 has r = 8 at s = 0 but row 3 has r = 8.5",
        ),
    ],
)
def test_a_law_that_does_not_close_is_refused(tmp_path, radius, says):
    """(c) On a closed axis: a law whose r or r' differs at the ends, a table that does not span
    the loop or whose ends differ: one line naming radius, exit 2, no file written."""
    text = CLOSED_TREFOIL.format(radius=radius)
    if "1400.0" in radius:  # the table's last row at the loop's end
        from tubecad.spec.parse import load_spec

        path = tmp_path / "probe.toml"
        path.write_text(CLOSED_TREFOIL.format(radius=8.0))
        text = text.replace("1400.0", repr(load_spec(path).tube.length))
    path = tmp_path / "spec.toml"
    path.write_text(text)
    out = tmp_path / "x.step"
    result = run("build", path, "-o", out)
    assert result.exit_code == 2 and says in result.output, result.output
    assert len(result.output.strip().splitlines()) == 1 and not out.exists()
    with pytest.raises(ParameterError, match="radius: on a closed axis"):
        CanalSurface(ParametricAxis(trefoil, (0.0, TWO_PI)), "0.3 + 0.001 * s")


@pytest.mark.slow
def test_the_closed_canal_sample_builds_to_step(sample_build):
    """(d) samples/saddle_canal_closed.toml: a closed axis, a radius law, [layout], [wall]."""
    result = sample_build(SAMPLE.stem)  # the suite's one build of the sample, to STEP and IGES
    out = result.folder / "a.step"
    assert result.exit_code == 0, result.output
    report = result.report()
    brep = report["brep"]
    assert brep["valid"] and brep["free_edges"] == 0 and brep["boolean_check"]["findings"] == {}
    assert brep["volume_relative_error"] < 1e-9 and brep["fit"]["max_deviation"] < 1e-8
    back = report["exports"][str(out)]
    assert back["valid"] and back["faces"] == brep["faces"] and back["volume_relative_error"] < 1e-6


def test_a_stringer_that_would_touch_its_own_start_is_refused_in_one_line(tmp_path):
    """On the saddle sample a stringer comes back 0.12 deg past its start, less than its
    angular width: `tubecad build` refuses it in one line, naming it, and writes nothing."""
    spec = tmp_path / "spec.toml"
    spec.write_text(SAMPLE.read_text() + "\n[stiffeners]\nstringers = [0]\nheight = 2.0\nthickness = 0.5\n")
    out = tmp_path / "c.step"
    result = run("build", spec, "-o", out, "-q")  # -q: no progress lines, the error alone
    assert result.exit_code == 2 and "would touch its own start where the closed canal wall closes" in result.output
    assert len(result.output.strip().splitlines()) == 1 and not out.exists()


@pytest.mark.slow
def test_ring_frames_all_round_a_closed_canal_wall_from_the_command_line(tmp_path):
    """`tubecad build` of the saddle sample with ring frames on all its rings: the closing ring
    once (9 layout rings on a closed axis are 8 rings), each part valid and passing the
    pre-boolean checks in the STEP read back, and the rings at t and 2 pi - t of one volume (the loop and its law
    are symmetric under the half turn about the x axis)."""
    import build123d as bd

    from tubecad.export.cad import import_shape

    spec = tmp_path / "spec.toml"
    spec.write_text(SAMPLE.read_text() + '\n[stiffeners]\nrings = "all"\nheight = 2.0\nthickness = 0.5\n')
    out = tmp_path / "c.step"
    result = run("build", spec, "-o", out, "-q")
    assert result.exit_code == 0, result.output
    solids = bd.Compound(import_shape(out)).solids()
    assert len(solids) == 1 + 8 and all(s.is_valid for s in solids)
    rings = sorted(solids, key=lambda s: s.volume)[:8]
    # every check but the self-intersection one, which the closing ring gets whole above
    assert all(props.analyzer_findings(ring, CHECKS) == {} for ring in rings)
    # the closing ring (t = 0, the largest r) and the ring at t = pi once each, the rest in pairs
    volumes = sorted(props.volume(r) for r in rings)
    pairs = volumes[1:7]
    assert all(a == pytest.approx(b, rel=1e-9) for a, b in zip(pairs[::2], pairs[1::2])), volumes  # measured 2e-11
    assert volumes[-1] > 1.05 * volumes[-2]
