"""The junction samples (issue 25) mesh and analyse from the command line: CalculiX solves each
pressurised junction (the tee's stiffeners as beams), its hoop stress far from the saddle (and
from ring frames) is membrane theory's (p a / t on a straight piece, the torus' on the bend;
a = r - t / 2, the face the pressure acts on) round every ring to 1 %, and the saddle's stress
concentration is reported."""

from __future__ import annotations

import json

import meshio
import numpy as np
import pytest
from click.testing import CliRunner
from conftest import ROOT

from tubecad.cli.app import cli

pytestmark = [pytest.mark.requires("gmsh"), pytest.mark.slow]


@pytest.mark.once
@pytest.mark.requires("ccx")
@pytest.mark.parametrize(
    ("sample", "checked", "concentration"),
    [
        # its stiffeners as beams: the main's ring means away from the saddle and the ring frames
        # within 0.74 % (2.6 % at a node, beside a stringer); the branch's two ring frames leave
        # none of its nodes 4 sqrt(r t) from them and the saddle; SCF 1.7 (the pad round the
        # opening). Shell alone (measured last stop): 0.47 % and 0.48 %, SCF 1.9
        ("tee", ("main",), (1.5, 2.5)),
        # within 0.46 % and 0.67 %; SCF 7.7 at the 45 deg lateral's acute crotch
        ("lateral", ("main", "branch"), (5.0, 10.0)),
        # the torus main within 0.32 % (its crown's boundary layer: 1.8 % at a node); the 100 mm
        # nozzle has no ring 4 sqrt(r t) from both its saddle and its end; SCF 2.6
        ("nozzle_on_torus", ("main",), (2.0, 3.5)),
        # the equal tee (issue 43): the main's ring means within 0.53 %; SCF 2.2 near the crotch,
        # where the mid-surfaces touch
        ("equal_tee", ("main",), (1.5, 3.0)),
        # the cross and the wye: both branches' ring means within 0.57 % and 0.63 %; SCF 3.9 and 4.8
        ("cross", ("main", "branch_0", "branch_1"), (3.0, 5.0)),
        ("wye", ("main", "branch_0", "branch_1"), (4.0, 6.0)),
    ],
)
def test_a_junction_sample_analyses_from_the_command_line(tmp_path, sample, checked, concentration):
    out = tmp_path / sample
    result = CliRunner().invoke(cli, ["analyse", str(ROOT / "samples" / f"{sample}.toml"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "results.json").read_text())
    junction = summary["junction"]
    for name in checked:
        entry = junction["membrane"][name]
        assert entry["whole_rings"] >= 3, (name, entry)
        assert entry["ring_mean_max_relative_error"] < 0.01, (name, entry)
    low, high = concentration
    assert low < junction["saddle"]["stress_concentration"] < high
    assert f"{junction['saddle']['stress_concentration']:.3g} x the main's hoop stress" in result.output
    assert sorted(p.name for p in out.iterdir()) == sorted(summary["files"])


@pytest.mark.parametrize("sample", ["tee", "lateral", "nozzle_on_torus", "equal_tee"])
def test_a_junction_sample_meshes_with_its_sets(tmp_path, sample):
    """tubecad mesh writes the .inp, .msh and .vtu; meshio reads the .vtu back with every
    element; the deck names the saddle, the ends (and the tee's pad) and gives every element
    node its normal: a unit vector, and on the saddle nodes two different ones (the knot)."""
    files = [tmp_path / f"{sample}.{ext}" for ext in ("inp", "msh", "vtu")]
    args = ["mesh", str(ROOT / "samples" / f"{sample}.toml")] + [a for f in files for a in ("-o", str(f))]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    count = int(result.output.split(" elements")[0])
    assert sum(len(c.data) for c in meshio.read(files[2]).cells) == count
    deck = files[0].read_text()
    sets = {line.split("NSET=")[1].strip() for line in deck.splitlines() if line.startswith("*NSET, NSET=")}
    assert {"saddle", "main_start", "main_end", "branch_end"} <= sets
    assert ("pad" in sets) == (sample in ("tee", "equal_tee"))
    assert ("*BEAM SECTION" in deck) == (sample in ("tee", "equal_tee"))  # the stiffeners, as beams
    # an equal tee's crotch: the two saddle nodes where the mid-surfaces touch, (300, +-50, 0)
    assert ("crotch" in sets) == (sample == "equal_tee")
    if sample == "equal_tee":
        nodes = _nodes(deck)
        crotch = np.array(sorted((nodes[n] for n in _set(deck, "crotch")), key=lambda p: p[1]))
        assert np.abs(crotch - [[300.0, -50.0, 0.0], [300.0, 50.0, 0.0]]).max() < 1e-9  # measured 5.2e-15
        assert set(_set(deck, "crotch")) <= set(_set(deck, "saddle").tolist())
    saddle = _set(deck, "saddle")
    normals = deck.split("*NORMAL\n", 1)[1].split("*", 1)[0].strip().splitlines()
    rows = np.array([[float(v) for v in line.split(",")] for line in normals])
    assert np.abs(np.linalg.norm(rows[:, 2:], axis=1) - 1).max() < 1e-12
    at_saddle = rows[np.isin(rows[:, 1].astype(int), saddle)]
    crotch = set(_set(deck, "crotch").tolist()) if sample == "equal_tee" else set()
    spread = {int(n): at_saddle[at_saddle[:, 1] == n, 2:] for n in [m for m in saddle if m not in crotch][:5]}
    for n, vectors in spread.items():
        assert np.ptp(vectors, axis=0).max() > 0.1, n  # the main's and the branch's normals meet at an angle
    for n in crotch:  # where the mid-surfaces touch, the two tubes' normals agree
        assert np.ptp(at_saddle[at_saddle[:, 1] == n, 2:], axis=0).max() < 1e-9, n


def _nodes(deck: str) -> dict[int, np.ndarray]:
    block = deck.split("*NODE", 1)[1].split("\n", 1)[1].split("*", 1)[0]
    rows = (line.split(",") for line in block.strip().splitlines())
    return {int(r[0]): np.array([float(v) for v in r[1:4]]) for r in rows}


def _set(deck: str, name: str) -> np.ndarray:
    block = deck.split(f"*NSET, NSET={name}\n", 1)[1].split("*", 1)[0]
    return np.array([int(v) for v in block.replace("\n", ",").split(",") if v.strip()])
