"""Every output format tubecad writes, by file extension: the one table the command line
(``-o``, batch ``-f``), :func:`tubecad.export.cad.export_shape`, the error messages and the
README's list come from.

- ``cad``: exact B-rep (STEP, IGES, BREP), read back and measured against the exact tube;
- ``mesh``: triangles for visual use (STL, 3MF, glTF), read back and their vertices checked;
- ``polylines``: the curvature lines as points with unit tangents and normals (CSV, JSON).

:func:`write_output` writes to a temporary file beside the target, runs an optional check
on it, and only then moves it into place: a file that fails its check is never left behind.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from ..errors import ParameterError
from ..units import DEFAULT_LENGTH_UNIT
from .atomic import atomic_path


@dataclass
class Exportable:
    """What an output is made from: the shape (a solid, or a build123d assembly with names
    and colours), the curvature lines for the polyline formats, and the writers' options.

    ``length_unit``: the unit of the model's coordinates (tubecad.units), which every format
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


@dataclass(frozen=True)
class OutputFormat:
    name: str
    extensions: tuple[str, ...]
    kind: str  # cad | mesh | polylines
    description: str
    write: Callable[[Exportable, Path, str], None]  # (item, path, product name)


def _cad(fmt: str):
    def write(item: Exportable, path: Path, name: str) -> None:
        from .cad import write_cad

        write_cad(fmt, _shape(item, path), path, item.step_schema, name, item.length_unit)

    return write


def _mesh(fmt: str):
    def write(item: Exportable, path: Path, name: str) -> None:
        from .mesh import write_mesh

        from .meshing import ANGULAR_DEFLECTION

        angular = ANGULAR_DEFLECTION if item.mesh_angular is None else item.mesh_angular
        write_mesh(fmt, _shape(item, path), path, item.mesh_deflection, angular, item.length_unit, item.build)

    return write


def _polylines(fmt: str):
    def write(item: Exportable, path: Path, name: str) -> None:
        from ..stiffeners.lines import polylines_csv_text, polylines_json_text

        if item.lines is None:
            raise ParameterError(f"output {path.name!r}: {fmt.upper()} holds curvature lines; this output has none")
        lines = item.lines()
        text = polylines_csv_text(lines) if fmt == "csv" else polylines_json_text(lines, length_unit=item.length_unit)
        path.write_text(text, encoding="utf-8")

    return write


def _shape(item: Exportable, path: Path):
    if item.shape is None:
        raise ParameterError(f"output {path.name!r}: this output has no shape to write")
    return item.shape


FORMATS: tuple[OutputFormat, ...] = (
    OutputFormat("step", (".step", ".stp"), "cad", "AP214 or AP242 (`--step-schema`), in `[units] length`, product "
                 "names and colours; about 14 significant digits", _cad("step")),
    OutputFormat("iges", (".iges", ".igs"), "cad", "B-rep entities (solids, shells), in `[units] length`; 13 "
                 "significant digits (about as closely as STEP)", _cad("iges")),
    OutputFormat("brep", (".brep",), "cad", "OCCT's own format: every digit of a double", _cad("brep")),
    OutputFormat("stl", (".stl",), "mesh", "binary STL, 32-bit floats, for viewing and printing", _mesh("stl")),
    OutputFormat("3mf", (".3mf",), "mesh", "one mesh per solid, with its name and colour, in `[units] length`",
                 _mesh("3mf")),
    OutputFormat("gltf", (".gltf",), "mesh", "glTF 2.0 text with the buffer embedded: one file (metres, Y up)",
                 _mesh("gltf")),
    OutputFormat("glb", (".glb",), "mesh", "glTF 2.0 binary (metres, Y up)", _mesh("glb")),
    OutputFormat("csv", (".csv",), "polylines", "the curvature lines on every wall surface: points, unit tangents and "
                 "normals, a row per point", _polylines("csv")),
    OutputFormat("json", (".json",), "polylines", "the same, a list of lines", _polylines("json")),
)  # fmt: skip

#: every extension (with the dot, lower case) -> its format
EXTENSIONS: dict[str, OutputFormat] = {ext: f for f in FORMATS for ext in f.extensions}
#: what batch ``-f/--format`` accepts: the extensions without the dot
FORMAT_NAMES: tuple[str, ...] = tuple(ext[1:] for ext in EXTENSIONS)


def allowed() -> str:
    """The allowed extensions, for messages: '.step, .stp, .iges, ...'."""
    return ", ".join(EXTENSIONS)


def output_format(path: str | Path) -> OutputFormat:
    """The format of an output path from its extension, or a ParameterError listing every one."""
    suffix = Path(path).suffix.lower()
    fmt = EXTENSIONS.get(suffix)
    if fmt is None:
        what = f"unknown extension {suffix!r}" if suffix else "no extension"
        raise ParameterError(f"output {str(path)!r}: {what}; use one of {allowed()}")
    return fmt


def write_output(item: Exportable, path: str | Path, check: Callable[[Path, OutputFormat], Any] | None = None
                 ) -> tuple[Path, Any]:  # fmt: skip
    """Write ``item`` to ``path`` in the format of its extension, atomically. ``check(tmp, fmt)``
    runs on the complete temporary file before it replaces ``path``; if it raises, no file is
    left. Returns (path, what check returned)."""
    path = Path(path)
    fmt = output_format(path)
    with atomic_path(path) as tmp:
        fmt.write(item, tmp, item.name or path.stem)
        result = check(tmp, fmt) if check is not None else None
    return path, result


KIND_NAMES = {"cad": "exact B-rep", "mesh": "mesh (visual)", "polylines": "polylines"}


def markdown_table() -> str:
    """The formats as the README's table (a test keeps the README equal to it)."""
    rows = ["| extension | kind | what it holds |", "|---|---|---|"]
    rows += [f"| {', '.join(f'`{e}`' for e in f.extensions)} | {KIND_NAMES[f.kind]} | {f.description} |" for f in FORMATS]
    return "\n".join(rows)
