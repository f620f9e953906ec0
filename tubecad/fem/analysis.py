"""The pressure analysis: the model and its step written, CalculiX run, the results read
back onto the mesh's nodes, and the membrane stresses along the net.

On the curvature-line net the principal directions are the ring and stringer tangents at
every node, so sigma_ring = e_ring . S e_ring and sigma_stringer = e_str . S e_str are the
membrane stresses the shell theory of docs/MATH.md section 10 gives in closed form
(cylinder: p r / t and p r / 2t; torus: p r (2 R + r sin theta) / (2 t (R + r sin theta))
and p r / 2t).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tubecad.fem.calculix import directional, read_frd, run_ccx, stress_tensors
from tubecad.fem.inp import Material, Step, write_inp
from tubecad.fem.model import FEMesh


@dataclass
class PressureResult:
    """Per node of the mesh: ``displacement`` (n, 3), ``stress`` (n, 3, 3, global),
    ``ring_stress`` and ``stringer_stress`` (n,): the normal stresses along the net."""

    mesh: FEMesh
    displacement: np.ndarray
    stress: np.ndarray
    ring_stress: np.ndarray
    stringer_stress: np.ndarray
    seconds: float

    def summary(self) -> dict:
        u = np.linalg.norm(self.displacement, axis=1)
        shells = np.unique(np.concatenate([b.connectivity.ravel() for b in self.mesh.shell_blocks]))

        def extent(v: np.ndarray) -> dict:
            v = v[shells]
            return {"min": float(np.nanmin(v)), "max": float(np.nanmax(v)), "mean": float(np.nanmean(v))}

        return {
            "nodes": len(self.mesh.nodes),
            "elements": self.mesh.element_count,
            "solve_seconds": self.seconds,
            "max_displacement": float(u.max()),
            "ring_stress": extent(self.ring_stress),
            "stringer_stress": extent(self.stringer_stress),
        }


def solve(
    mesh: FEMesh,
    material: Material,
    step: Step,
    folder: str | Path | None = None,
    name: str = "model",
    timeout: float = 1800.0,
) -> PressureResult:
    """Write ``mesh`` with ``material`` and ``step`` as ``name``.inp in ``folder`` (a temporary
    folder when None), solve it with ccx, and read the displacements and stresses back."""
    import time

    with tempfile.TemporaryDirectory(prefix="tubecad-ccx-") as tmp:
        where = Path(folder) if folder is not None else Path(tmp)
        where.mkdir(parents=True, exist_ok=True)
        deck = write_inp(mesh, where / f"{name}.inp", material, step)
        start = time.perf_counter()
        frd = run_ccx(deck, timeout=timeout)
        seconds = time.perf_counter() - start
        blocks = read_frd(frd)
    disp = np.full((len(mesh.nodes), 3), np.nan)
    disp[blocks["DISP"].nodes] = blocks["DISP"].values[:, :3]
    stress = stress_tensors(blocks["STRESS"], len(mesh.nodes))
    return PressureResult(
        mesh,
        disp,
        stress,
        directional(stress, mesh.ring_tangents),
        directional(stress, mesh.stringer_tangents),
        seconds,
    )
