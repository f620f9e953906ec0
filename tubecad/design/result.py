"""The build result protocol, and writing any build result's files.

Every design builds into a :class:`BuildResult` (a tube or wall:
:class:`~tubecad.design.wall.WallResult`; a junction:
:class:`~tubecad.design.junction.JunctionResult`), so export, read-back, the report, the
parts and batches each have one path: :func:`write_outputs` writes every output of any of
them, each read back by the result's own :meth:`BuildResult.check_file` before it is moved
into place.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from tubecad.core.progress import Progress
from tubecad.design.stages import stage

if TYPE_CHECKING:
    from tubecad.export.registry import Exportable, OutputFormat


class BuildResult(Protocol):
    """What a design built: its solids and named edges, the shape its files are written
    from, the exact surfaces it was built about, and what was measured."""

    #: the shape every file is written from (a solid, or the named assembly)
    shape: Any
    #: what was measured (the exact surface's measures, the B-rep's in ``brep``, ...)
    report: dict[str, Any]

    @property
    def kind(self) -> str:
        """``tube_solid``, ``wall`` or ``junction_wall``."""
        ...

    @property
    def length_unit(self) -> str:
        """The unit of the coordinates, stated by every file."""
        ...

    @property
    def surfaces(self) -> list[Any]:
        """The exact curvature-line surfaces the build was made about (the main one first)."""
        ...

    @property
    def solids(self) -> list[tuple[str, Any]]:
        """(name, OCCT solid) of every solid, the wall first (``wall``, ``ring_03``, ``pad``...)."""
        ...

    @property
    def named_edges(self) -> dict[str, list[Any]]:
        """The wall solid's named edges (OCCT edges) by name (``ring_03``, ``saddle_outer``...)."""
        ...

    @property
    def mesh_radius(self) -> float:
        """The smallest radius of the walls' surfaces: mesh tolerances are checked against it."""
        ...

    def lines(self) -> list[Any]:
        """The curvature lines written by the polyline formats."""
        ...

    def exportable(self, step_schema: str, deflection: float, angular: float) -> Exportable:
        """What every output is written from (tubecad.export.registry)."""
        ...

    def written_reference(self) -> Any:
        """The shape written, with what is known of it (:class:`~tubecad.export.readback.WrittenShape`)."""
        ...

    def check_file(
        self, tmp: Path, fmt: OutputFormat, target: Path, reference: Any, deflection: float, angular: float
    ) -> dict[str, Any]:
        """Read the just-written ``tmp`` (for ``target``) back and measure it; raise if it does
        not hold what was built, so it is never moved into place."""
        ...


def mesh_tolerances(
    result: BuildResult, deflection: float | None = None, angle_deg: float | None = None
) -> tuple[float, float]:
    """(linear deflection, angular deflection in radians) of ``result``'s mesh outputs:
    those asked for, checked, or the defaults (tubecad.export.meshing.checked_tolerance)."""
    from tubecad.export.meshing import checked_tolerance

    return checked_tolerance(deflection, angle_deg, result.mesh_radius)[:2]


def write_outputs(
    result: BuildResult,
    outputs: Sequence[str | Path],
    step_schema: str = "AP214",
    deflection: float | None = None,
    angular: float | None = None,
    written: list[Path] | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Write ``result``'s shape to each of ``outputs`` (the format by extension), each read
    back and measured by the result before it is moved into place (never a partial or
    unchecked file); returns what was measured per file (also ``result.report["exports"]``).

    Args:
        result: any build result.
        outputs: the files to write.
        step_schema: STEP's application protocol (``AP214``, ``AP203``, ``AP242``).
        deflection: the mesh outputs' linear deflection (model units; None: the default).
        angular: the mesh outputs' angular deflection (radians; None: the default).
        written: each path is appended once it is complete.
        progress: hears of each file written and checked.

    Returns:
        {path: what was measured on the file read back}.
    """
    from functools import partial

    from tubecad.export.registry import write_output

    written = [] if written is None else written
    progress = progress if progress is not None else Progress(enabled=False)
    if deflection is None or angular is None:
        default = mesh_tolerances(result)
        deflection, angular = deflection or default[0], angular or default[1]
    exports = result.report["exports"] = {}
    item = result.exportable(step_schema, deflection, angular)
    reference = result.written_reference()  # its area and volume integrated once for all the files

    def check(tmp: Path, fmt: OutputFormat, path: Path) -> dict[str, Any]:
        progress.advance(1, f"wrote {path.name}")
        return result.check_file(tmp, fmt, path, reference, deflection, angular)

    progress.step("writing and reading back files", 2 * len(outputs))
    for path in map(Path, outputs):  # STEP of an assembly keeps its names: wall, ring_03, line_ring_03, ...
        with stage("export"):  # a file that does not hold the build: the fit tolerance or the unit at fault
            done, info = write_output(item, path, partial(check, path=path))
        written.append(done)
        exports[str(path)] = info
        progress.advance(1, f"checked {path.name}")
    return exports
