"""The sample scripts run as users would run them, and do what they say."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

SAMPLES = Path(__file__).parent.parent / "samples"


def test_build123d_sample_writes_the_curvature_net_to_step(tmp_path):
    import build123d as bd

    out = tmp_path / "net.step"
    done = subprocess.run([sys.executable, str(SAMPLES / "build123d_curvature_net.py"), str(out),
                           "--rings", "5", "--stringers", "4"], capture_output=True, text=True, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    worst = float(re.search(r"crossings: ([\d.e+-]+)", done.stdout).group(1))
    assert worst < 1e-4  # rings and stringers cross at right angles
    net = bd.import_step(out)
    edges = net.edges()
    assert len(edges) == 5 + 4
    circles = [e for e in edges if e.geom_type == bd.GeomType.CIRCLE]
    assert len(circles) == 5 and all(e.radius == pytest.approx(15.0, rel=1e-9) for e in circles)
