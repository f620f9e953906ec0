"""Running CalculiX (``ccx``) on a deck and reading its results back (``.frd``).

The ``.frd`` reader is the few lines the format needs (fixed-width ASCII): a result block
starts with ``-4  NAME  ncomp``, lists its components on ``-5`` lines and its values on
``-1`` lines (node number in columns 4-13, then 12-character numbers), and ends with ``-3``.
With ``OUTPUT=2D`` the values are those of the shell's own nodes: displacements of the
reference surface, stresses averaged through the expanded element's thickness (the
membrane stresses, the bending part cancelling).
"""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tubecad.core.errors import TubecadError


class CalculixError(TubecadError):
    """ccx is missing, failed, or wrote no results."""


@dataclass(frozen=True)
class FrdBlock:
    """One result block: ``nodes`` (0-based), ``values`` (n, components), component names."""

    name: str
    components: tuple[str, ...]
    nodes: np.ndarray
    values: np.ndarray


def ccx_executable() -> str:
    """The path of ``ccx`` (CalculiX's solver), or a CalculixError saying how to install it."""
    exe = shutil.which("ccx")
    if exe is None:
        raise CalculixError(
            "CalculiX (ccx) is not installed: apt-get install calculix-ccx (Debian/Ubuntu), "
            "or conda install -c conda-forge calculix"
        )
    return exe


def run_ccx(deck: str | Path, timeout: float = 600.0, threads: int | None = None) -> Path:
    """Solve ``deck`` (``NAME.inp``) in its folder; returns ``NAME.frd``. A CalculixError
    carries the end of ccx's output when it fails."""
    import os

    deck = Path(deck)
    env = dict(os.environ)
    if threads is not None:
        env["OMP_NUM_THREADS"] = env["CCX_NPROC_EQUATION_SOLVER"] = str(threads)
    proc = subprocess.run(
        [ccx_executable(), "-i", deck.stem], cwd=deck.parent, capture_output=True, text=True, timeout=timeout, env=env
    )
    frd = deck.with_suffix(".frd")
    tail = (proc.stdout + proc.stderr)[-1500:]
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not frd.exists():
        raise CalculixError(f"ccx failed on {deck.name} (exit {proc.returncode}):\n{tail}")
    return frd


def read_frd(path: str | Path) -> dict[str, FrdBlock]:
    """The nodal result blocks of a ``.frd`` file by name (DISP, STRESS, ...; the last step's)."""
    blocks: dict[str, FrdBlock] = {}
    name: str | None = None
    comps: list[str] = []
    nodes: list[int] = []
    rows: list[list[float]] = []
    with open(path, encoding="ascii", errors="replace") as fh:
        for line in fh:
            key = line[:3]
            if key == " -4":
                name, comps, nodes, rows = line[5:13].strip(), [], [], []
            elif key == " -5" and name is not None:
                comps.append(line[5:13].strip())
            elif key == " -1" and name is not None:
                nodes.append(int(line[3:13]))
                body = line[13:].rstrip("\n")
                rows.append([float(body[i : i + 12]) for i in range(0, len(body) - len(body) % 12, 12)])
            elif key == " -3" and name is not None:
                width = min(len(r) for r in rows) if rows else 0
                values = np.array([r[:width] for r in rows]) if rows else np.zeros((0, 0))
                blocks[name] = FrdBlock(name, tuple(comps[:width]), np.array(nodes, dtype=np.int64) - 1, values)
                name = None
    if not blocks:
        raise CalculixError(f"{path}: no results in the .frd file")
    return blocks


def stress_tensors(block: FrdBlock, count: int) -> np.ndarray:
    """(count, 3, 3) stress tensors per node from a STRESS block (SXX SYY SZZ SXY SYZ SZX)."""
    s = np.full((count, 3, 3), np.nan)
    xx, yy, zz, xy, yz, zx = block.values[:, :6].T
    n = block.nodes
    s[n, 0, 0], s[n, 1, 1], s[n, 2, 2] = xx, yy, zz
    s[n, 0, 1] = s[n, 1, 0] = xy
    s[n, 1, 2] = s[n, 2, 1] = yz
    s[n, 2, 0] = s[n, 0, 2] = zx
    return s


def directional(tensors: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """d^T S d per node: the normal stress along unit ``directions`` (n, 3)."""
    return np.einsum("ni,nij,nj->n", directions, tensors, directions)
