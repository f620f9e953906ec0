"""The new axis kinds from spec files (issue 11), from the command line: bad keys are refused in
one line naming the key, exit code 2, no file."""

import shutil

import pytest
from conftest import ROOT, assert_build_refused

SAMPLES = ROOT / "samples"


BASE = {
    "natural": '[axis]\ncurve = "natural"\nk = "0.01"\ntau = "0.002"\ns = [0.0, 300.0]\n',
    "parametric": '[axis]\ncurve = "parametric"\nx = "100 * cos(t)"\ny = "100 * sin(t)"\nz = "20 * t"\nt = [0.0, 3.0]\n',
    "points": '[axis]\ncurve = "points"\npoints = [[0, 0, 0], [100, 0, 10], [200, 50, 20]]\n',
}
TUBE = "[tube]\nradius = 5.0\n"


@pytest.mark.parametrize(
    "text, says",
    [
        (
            BASE["natural"].replace('k = "0.01"', 'k = "1 / (s - 100)"'),
            "[axis] k(s) could not be resolved to 1e-15 with 2048 panels on [0, 300]: it must be smooth and finite there, and it is not near s = 100",
        ),
        (BASE["natural"].replace('tau = "0.002"', 'tau = "sqrt(-1 - s)"'), "[axis] tau(s) is not finite"),
        pytest.param(  # refused by the regularity scan of a tightly coiled axis: slow
            BASE["natural"].replace('k = "0.01"', 'k = "0.5"'), "[tube] radius 5: ", marks=pytest.mark.slow
        ),
        (BASE["parametric"].replace('z = "20 * t"', 'z = "u"'), "unknown name 'u'"),
        (
            BASE["parametric"]
            .replace('x = "100 * cos(t)"', 'x = "(t - 1)**3"')
            .replace('y = "100 * sin(t)"', 'y = "(t - 1)**2"')
            .replace('z = "20 * t"', 'z = "0"'),
            "is degenerate: its speed |dx/dt| is",
        ),
        (BASE["parametric"].replace("t = [0.0, 3.0]", "t = [3.0, 0.0]"), "[axis] t must"),
        (BASE["points"].replace("[100, 0, 10]", "[0, 0, 0]"), "[axis] points[1] [0, 0, 0] repeats points[0]"),
        (
            BASE["points"].replace(
                "points = [[0, 0, 0], [100, 0, 10], [200, 50, 20]]", "points = [[0, 0, 0], [1, 1, 1]]"
            ),
            "[axis] points must be a list of three or more [x, y, z] points",
        ),
        (BASE["points"] + 'file = "p.csv"\n', "give either points"),
        (
            BASE["points"] + 'parameterisation = "uniform"\n',
            "[axis] parameterisation must be one of centripetal, chord",
        ),
        ('[axis]\ncurve = "edge"\nfile = "missing.step"\n', "[axis] file 'missing.step' not found"),
        ('[axis]\ncurve = "edge"\nfile = "centreline.step"\nindex = 3\n', "[axis] index must be in 0 to 0"),
        ('[axis]\ncurve = "edge"\nfile = "centreline.step"\nname = "nothing"\n', "[axis] name 'nothing' is not in"),
        ('[axis]\ncurve = "edge"\nfile = "empty.step"\n', "holds no edge or wire"),
        ('[axis]\ncurve = "natural"\nk = "0.01"\ns = [0.0, 300.0]\n', "[axis] tau is missing"),
        (
            '[axis]\ncurve = "parametric"\nx = "t"\ny = "0"\nz = "0"\nt = [0.0, 3.0]\nbeta_deg = 10.0\n',
            "unknown key [axis] beta_deg",
        ),
    ],
)
def test_bad_axis_keys_exit_2_in_one_line_and_write_nothing(text, says, tmp_path):
    import build123d as bd

    shutil.copy(SAMPLES / "centreline.step", tmp_path / "centreline.step")
    bd.export_step(bd.Box(1, 1, 1).vertices()[0], str(tmp_path / "empty.step"))  # a point: no edge
    assert_build_refused(tmp_path, text + TUBE, says)


def test_a_loop_kept_open_is_refused_as_its_end_caps_would_coincide(tmp_path):
    """The whole trefoil knot (t in [0, 2 pi]) ends where it starts; with ``closed = false``
    it is an open tube whose end discs would coincide: refused in one line."""
    text = (
        '[axis]\ncurve = "parametric"\nx = "40 * (sin(t) + 2 * sin(2 * t))"\ny = "40 * (cos(t) - 2 * cos(2 * t))"\n'
        'z = "-40 * sin(3 * t)"\nt = [0.0, 6.283185307179586]\nclosed = false\n'
    )
    assert_build_refused(tmp_path, text + "[tube]\nradius = 8.0\n", "the end caps would coincide")
