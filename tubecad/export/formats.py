"""Every output format tubecad writes, by file extension: the one table the command line
(``-o``, batch ``-f``), the writers (:mod:`.registry`), the readers (:mod:`.cad`), the batch
manifest, the error messages and the docs' list come from. Pure data: it loads nothing.

- ``cad``: exact B-rep (STEP, IGES, BREP), read back and measured against the exact tube;
- ``mesh``: triangles for visual use (STL, 3MF, glTF), read back and their vertices checked;
- ``polylines``: the curvature lines as points with unit tangents and normals (CSV, JSON);
- ``picture``: the frontal and horizontal projections with the curvature-line net (PNG, SVG).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tubecad.core.errors import ParameterError


@dataclass(frozen=True)
class OutputFormat:
    name: str
    extensions: tuple[str, ...]
    kind: str  # cad | mesh | polylines | picture
    description: str


FORMATS: tuple[OutputFormat, ...] = (
    OutputFormat(
        "step",
        (".step", ".stp"),
        "cad",
        "AP214 or AP242 (`--step-schema`), in `[units] length`, product names and colours; 17 significant digits: a double to the bit",
    ),
    OutputFormat(
        "iges",
        (".iges", ".igs"),
        "cad",
        "B-rep entities (solids, shells), in `[units] length`; 17 significant digits: a double to the bit (a file about 2.7 x OCCT's own IGES)",
    ),
    OutputFormat("brep", (".brep",), "cad", "OCCT's own format: every digit of a double"),
    OutputFormat("stl", (".stl",), "mesh", "binary STL, 32-bit floats, for viewing and printing"),
    OutputFormat("3mf", (".3mf",), "mesh", "one mesh per solid, with its name and colour, in `[units] length`"),
    OutputFormat("gltf", (".gltf",), "mesh", "glTF 2.0 text with the buffer embedded: one file (metres, Y up)"),
    OutputFormat("glb", (".glb",), "mesh", "glTF 2.0 binary (metres, Y up)"),
    OutputFormat(
        "csv",
        (".csv",),
        "polylines",
        "the curvature lines on every wall surface: points, unit tangents and normals, a row per point",
    ),
    OutputFormat("json", (".json",), "polylines", "the same, a list of lines"),
    OutputFormat(
        "png",
        (".png",),
        "picture",
        "the frontal and horizontal projections of the outer surface with its ring frames and stringers",
    ),
    OutputFormat("svg", (".svg",), "picture", "the same, as vector graphics"),
)

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


def cad_format(path: str | Path) -> str:
    """'step', 'iges' or 'brep' from the extension; a ParameterError listing every extension
    tubecad writes for an unknown one, and the B-rep ones for a mesh or polyline extension."""
    fmt = output_format(path)  # an unknown extension: the error lists them all
    if fmt.kind != "cad":
        cad = ", ".join(ext for f in FORMATS if f.kind == "cad" for ext in f.extensions)
        raise ParameterError(f"output {str(path)!r}: {Path(path).suffix} is not a B-rep format; use one of {cad}")
    return fmt.name


KIND_NAMES = {"cad": "exact B-rep", "mesh": "mesh (visual)", "polylines": "polylines", "picture": "picture"}


def markdown_table() -> str:
    """The formats as the docs' table (a test keeps the docs equal to it)."""
    rows = ["| extension | kind | what it holds |", "|---|---|---|"]
    rows += [
        f"| {', '.join(f'`{e}`' for e in f.extensions)} | {KIND_NAMES[f.kind]} | {f.description} |" for f in FORMATS
    ]
    return "\n".join(rows)
