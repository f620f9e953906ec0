"""Writing outputs: each format of :mod:`.formats` (the one table of extensions) mapped to its
writer, and :func:`export_shape`, the front door for any shape.

:func:`write_output` writes to a temporary file beside the target, runs an optional check
on it, and only then moves it into place: a file that fails its check is never left behind.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tubecad.core.atomic import atomic_path
from tubecad.core.errors import ParameterError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.export.formats import (
    EXTENSIONS,
    FORMAT_NAMES,
    FORMATS,
    KIND_NAMES,
    OutputFormat,
    allowed,
    cad_format,
    markdown_table,
    output_format,
)

__all__ = [
    "Exportable",
    "WRITERS",
    "write_output",
    "export_shape",
    "EXTENSIONS",
    "FORMAT_NAMES",
    "FORMATS",
    "KIND_NAMES",
    "OutputFormat",
    "allowed",
    "cad_format",
    "markdown_table",
    "output_format",
]

#: (item, path, product name) -> None; the product name is for the formats that record one (CAD)
Writer = Callable[["Exportable", Path, str], None]


@dataclass
class Exportable:
    """What an output is made from: the shape (a solid, or a build123d assembly with names
    and colours), the curvature lines for the polyline formats, and the writers' options.

    ``length_unit``: the unit of the model's coordinates (tubecad.core.units), which every format
    that records a unit states (STEP, IGES, 3MF; glTF is scaled to its metres); the
    coordinates themselves are written as they are."""

    shape: Any = None
    lines: Callable[[], list] | None = None  # the CurvatureLines, made when a polyline file asks
    step_schema: str = "AP214"
    name: str | None = None  # product name in STEP; default: the file's stem
    mesh_deflection: float | None = None  # model units; default: tubecad.export.mesh.default_deflection
    mesh_angular: float | None = None  # radians; default: tubecad.export.meshing.ANGULAR_DEFLECTION
    build: Any = None  # the TubeBuild of the shape's tube or wall: meshed on its curvature-line grid
    length_unit: str = DEFAULT_LENGTH_UNIT
    #: points marked on a picture with a label each (a net's umbilics and their types)
    marks: tuple[tuple[tuple[float, float, float], str], ...] = ()


def _cad(fmt: str) -> Writer:
    def write(item: Exportable, path: Path, name: str) -> None:
        from tubecad.export.cad import write_cad

        write_cad(fmt, _shape(item, path), path, item.step_schema, name, item.length_unit)

    return write


def _mesh(fmt: str) -> Writer:
    def write(item: Exportable, path: Path, _name: str) -> None:
        from tubecad.export.mesh import write_mesh
        from tubecad.export.meshing import ANGULAR_DEFLECTION

        angular = ANGULAR_DEFLECTION if item.mesh_angular is None else item.mesh_angular
        write_mesh(fmt, _shape(item, path), path, item.mesh_deflection, angular, item.length_unit, item.build)

    return write


def _polylines(fmt: str) -> Writer:
    def write(item: Exportable, path: Path, _name: str) -> None:
        from tubecad.stiffeners.lines import polylines_csv_text, polylines_json_text

        if item.lines is None:
            raise ParameterError(f"output {path.name!r}: {fmt.upper()} holds curvature lines; this output has none")
        lines = item.lines()
        text = polylines_csv_text(lines) if fmt == "csv" else polylines_json_text(lines, length_unit=item.length_unit)
        path.write_text(text, encoding="utf-8")

    return write


def _picture(fmt: str) -> Writer:
    def write(item: Exportable, path: Path, name: str) -> None:
        from tubecad.export.plots import projection_figure_of_build

        if item.build is None and fmt == "png" and item.shape is not None:  # any shape: shaded, its edges drawn
            from tubecad.export.render import render_shape_png

            render_shape_png(item.shape, path, title=name, marks=item.marks)
            return
        if item.build is None:
            raise ParameterError(f"output {path.name!r}: a {fmt.upper()} picture is drawn from a built tube or wall")
        fig = projection_figure_of_build(item.build)
        try:
            fig.savefig(path, format=fmt, dpi=150)
        finally:
            fig.clear()

    return write


def _shape(item: Exportable, path: Path) -> Any:
    if item.shape is None:
        raise ParameterError(f"output {path.name!r}: this output has no shape to write")
    return item.shape


#: a format's kind (tubecad.export.formats) -> the writer of a format of that kind
_WRITER_OF_KIND: dict[str, Callable[[str], Writer]] = {
    "cad": _cad,
    "mesh": _mesh,
    "polylines": _polylines,
    "picture": _picture,
}

#: format name -> its writer, for every format of the table (no format is named here)
WRITERS: dict[str, Writer] = {f.name: _WRITER_OF_KIND[f.kind](f.name) for f in FORMATS}


def write_output(
    item: Exportable, path: str | Path, check: Callable[[Path, OutputFormat], Any] | None = None
) -> tuple[Path, Any]:
    """Write ``item`` to ``path`` in the format of its extension, atomically. ``check(tmp, fmt)``
    runs on the complete temporary file before it replaces ``path``; if it raises, no file is
    left. Returns (path, what check returned)."""
    path = Path(path)
    fmt = output_format(path)
    with atomic_path(path) as tmp:
        WRITERS[fmt.name](item, tmp, item.name or path.stem)
        result = check(tmp, fmt) if check is not None else None
    return path, result


def export_shape(
    shape: object,
    path: str | Path,
    step_schema: str = "AP214",
    name: str | None = None,
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> Path:
    """Write ``shape`` (OCCT or build123d/CadQuery) to ``path`` in the format of its extension:
    STEP, IGES, BREP, or a mesh for visual use (STL, 3MF, glTF), see :data:`FORMATS`.
    ``name``: the product name in STEP (default: the file's stem); ``length_unit``: the unit of
    the shape's coordinates, which the file states (mm, cm, m, in, ft; tubecad.core.units).

    The file is written beside ``path`` and moved into place when complete: a failed
    export leaves no file.

    Args:
        shape: the shape to write: an OCCT ``TopoDS_Shape``, a build123d or CadQuery shape
            (a solid, a compound, a part such as :class:`~tubecad.parts.CurvatureWall`, or a
            named assembly, whose names and colours STEP keeps).
        path: the output file; its extension picks the format: .step/.stp, .iges/.igs,
            .brep, .stl, .3mf, .gltf, .glb, or .png (a shaded picture). The curvature-line
            formats (.csv, .json) and .svg need a build, not a shape, and are refused.
        step_schema: the STEP schema, ``"AP214"`` (default) or ``"AP242"``; ignored by the
            other formats.
        name: the product name recorded in STEP (default: the file's stem).
        length_unit: the unit of the shape's coordinates, stated in the file (STEP, IGES,
            3MF; glTF is scaled to metres): ``"mm"`` (default), ``"cm"``, ``"m"``, ``"in"``
            or ``"ft"``. The coordinates are not converted.

    Returns:
        The path written, as a :class:`~pathlib.Path`.

    Raises:
        ParameterError: an unknown extension (listing every allowed one), an unknown
            ``step_schema`` or ``length_unit``, or a format the shape cannot be written to.
        ExportError: OCCT could not translate or write the shape
            (:class:`tubecad.export.cad.ExportError`, a :class:`TubecadError`).
    """
    return write_output(Exportable(shape, step_schema=step_schema, name=name, length_unit=length_unit), path)[0]
