"""Read an exported file back and check it: the file, not the fit, is what is reported.

CAD files (STEP, IGES, BREP) are read back by OCCT and measured: validity, counts, volume
and area against the written shape, and, given the build, every tube face's own surface
sampled against the exact tube of its radius (tubecad.brep.measure): the max deviation and
the max |cos| between the isoparametric directions. A file that holds the surface less
accurately than the [fit] tolerance (STEP keeps about 14 significant digits, IGES less,
so at large coordinates the file can lose what the fit reached), or its isolines less
orthogonal than the fitted target, is refused with :class:`FileAccuracyError`.

Mesh files (STL, 3MF, glTF) are visual: they are read back by independent readers and
every vertex, and every triangle (at its centroid and edge midpoints), is checked to lie
within the mesh deflection of the exact tube (plain walls and tubes; an assembly's
stiffeners stand off the tube, so there only the count is given).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.brep import properties as props
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.export.cad import ExportError, import_shape

if TYPE_CHECKING:
    from OCP.TopoDS import TopoDS_Compound, TopoDS_Shape

    from tubecad.brep import TubeBuild

#: samples per file for the read-back measure (spread over the tube faces, at least 2 x 2 each)
READBACK_SAMPLES = 3000

ALTERNATIVES = {"step": "use BREP (full double precision)", "iges": "use STEP or BREP"}


class FileAccuracyError(ExportError):
    """A written file does not hold the geometry to the tolerance it was built to."""


@dataclass
class WrittenShape:
    """The shape a build's files are written from, with its area and volume each integrated
    once however many files are read back against it (BRepGProp over hundreds of B-spline
    faces takes seconds)."""

    shape: object
    _measures: dict[str, float] = field(default_factory=dict, repr=False)

    def area(self) -> float:
        if "area" not in self._measures:
            self._measures["area"] = props.area(self.shape)
        return self._measures["area"]

    def volume(self) -> float:
        if "volume" not in self._measures:
            self._measures["volume"] = props.volume(self.shape)
        return self._measures["volume"]


def readback_report(
    path: str | Path,
    written: object | WrittenShape,
    build: TubeBuild | None = None,
    target: str | Path | None = None,
    wall_solids: int | None = None,
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> dict[str, Any]:
    """Validity, counts, free edges, and volume/area relative to the written shape; with
    ``build`` (a TubeBuild) also the deviation and orthogonality measured on the file's tube
    faces, refused (FileAccuracyError naming ``target``, the path the user asked for) when
    above the build's tolerance or its fitted orthogonality. ``wall_solids``: the file holds an
    assembly whose first ``wall_solids`` solids are the wall (1, or one per panel); only
    their faces on the wall's tubes are measured (stiffeners are separate parts).
    ``length_unit``: the model's unit (tubecad.core.units), which the file is read back into.
    ``written``: the shape, or a :class:`WrittenShape` shared by the files of one build."""
    reference = written if isinstance(written, WrittenShape) else WrittenShape(written)
    shape = import_shape(path, length_unit)
    out: dict[str, Any] = {
        "bytes": Path(path).stat().st_size,
        "valid": props.is_valid(shape),
        "solids": props.count(shape, "solid"),
        "faces": props.count(shape, "face"),
        "edges": props.count(shape, "edge"),
        "free_edges": props.free_edges(shape),
        "area_relative_error": abs(props.area(shape) / reference.area() - 1.0),
    }
    if props.count(reference.shape, "solid"):
        out["volume_relative_error"] = abs(props.volume(shape) / reference.volume() - 1.0)
        if not out["valid"]:  # no command writes a solid that fails the validity check
            name = Path(target if target is not None else path).name
            raise _invalid_file(name, Path(target if target is not None else path), shape)
    if build is not None:
        out.update(measure_file(shape, build, Path(target if target is not None else path), wall_solids))
    return out


def _invalid_file(name: str, target: Path, shape: object) -> FileAccuracyError:
    """The refusal of a file whose solid reads back invalid. Where the format's digits hold
    coordinates this large only to about a tenth of the B-rep's edge tolerance or worse, the
    size is the cause, and a larger length unit (or BREP's full doubles) the cure."""
    from tubecad.core.tolerance import EDGE_TOLERANCE, WRITTEN_DIGITS, written_resolution
    from tubecad.export.registry import cad_format

    message = f"{name}: the solid read back fails OCCT's validity check (BRepCheck_Analyzer); nothing was written"
    fmt = cad_format(target)
    size = props.largest_coordinate(shape)
    held = written_resolution(size)
    if fmt in ("step", "iges") and held > EDGE_TOLERANCE / 10:
        return FileAccuracyError(
            f"{message}: {fmt.upper()}'s {WRITTEN_DIGITS} digits hold coordinates up to {size:.3g} only to {held:.1g}, "
            f"near the edge tolerance {EDGE_TOLERANCE:g}; {ALTERNATIVES[fmt]}, or a larger length unit",
            key="length_unit",
        )
    return FileAccuracyError(message)


def measure_file(shape: TopoDS_Shape, build: TubeBuild, target: Path, wall_solids: int | None = None) -> dict[str, Any]:
    """The file's tube faces against the exact tubes (build.radii on build's axis); raises
    FileAccuracyError when the file does not meet the build's tolerance or orthogonality.
    ``wall_solids``: see :func:`readback_report`."""
    from tubecad.brep.measure import measure_tube_faces, surface_levels, tube_faces
    from tubecad.core.tolerance import orthogonality_for
    from tubecad.export.registry import cad_format

    axis = build.surfaces[0].tube.axis
    named = wall_solids is not None
    if wall_solids is not None:  # the wall's solids come first in the file, in the order they were written
        shape = _first_solids(shape, wall_solids)
    level, levels = surface_levels(build)
    size = None if list(levels) == list(build.radii) else min(build.radii)  # a canal wall's levels are offsets
    m = measure_tube_faces(shape, axis, levels, READBACK_SAMPLES, every_face=not named, level=level, size=size)
    expected = None if named else sum(1 for _ in tube_faces(build.shape))
    limit_dev, limit_orth = build.tolerance, orthogonality_for(build.tolerance)
    out = {
        "measured_faces": m.faces,
        "samples": m.samples,
        "max_deviation": m.max_deviation,
        "max_orthogonality_error": m.max_orthogonality,
        "tolerance": limit_dev,
        "orthogonality_target": limit_orth,
    }
    fmt = cad_format(target)
    name, what = target.name, fmt.upper()
    better = f"{ALTERNATIVES[fmt]}, or a looser fit tolerance" if fmt in ALTERNATIVES else "use a looser fit tolerance"
    if (expected is not None and m.faces < expected) or len(m.per_radius) < len(set(levels)):
        raise FileAccuracyError(
            f"{name}: {what} read back without the wall's tube faces ({m.faces} found on the "
            f"radii {', '.join(f'{r:g}' for r in build.radii)})"
        )
    if m.max_deviation > limit_dev:
        raise FileAccuracyError(
            f"{name}: {what} holds the surface only to {m.max_deviation:.2g} at this size, above the fit tolerance "
            f"{limit_dev:g}; {better}",
            key="tolerance",
        )
    if m.max_orthogonality > limit_orth:
        raise FileAccuracyError(
            f"{name}: {what} holds the isolines orthogonal only to |cos| {m.max_orthogonality:.2g} at this size, above "
            f"the fitted {limit_orth:g} (from the fit tolerance {limit_dev:g}); {better}",
            key="tolerance",
        )
    return out


def mesh_report(
    path: str | Path,
    fmt: str,
    build: TubeBuild | None = None,
    deflection: float | None = None,
    target: str | Path | None = None,
    wall_solids: int | None = None,
    length_unit: str = DEFAULT_LENGTH_UNIT,
    angular: float | None = None,
) -> dict[str, Any]:
    """Triangles and vertices of a mesh file read back (into the model's ``length_unit``), and
    the tolerances it was meshed to (``deflection``, model units; ``angular``, radians). With
    ``build`` and no ``wall_solids`` (not an assembly): how far its vertices, and its triangles
    (centroids and edge midpoints), lie from the exact tubes; refused when the vertices are
    beyond ``deflection`` or the triangles beyond ``deflection`` plus what the vertices are off
    (the file's 32-bit floats)."""
    from tubecad.export.mesh import read_mesh_triangles
    from tubecad.export.tessellate import mesh_deviation

    vertices, triangles = read_mesh_triangles(path, fmt, length_unit)
    target = Path(target if target is not None else path)
    if not len(triangles):
        raise FileAccuracyError(f"{target.name}: {fmt.upper()} read back with no triangles")
    out: dict[str, Any] = {
        "bytes": Path(path).stat().st_size,
        "mesh": "visual (triangles, 32-bit floats)",
        "triangles": int(len(triangles)),
        "vertices": int(len(vertices)),
        "deflection": deflection,
        "angular_deflection_deg": None if angular is None else math.degrees(angular),
    }
    if build is not None and wall_solids is None:
        from tubecad.brep.measure import surface_levels

        level, levels = surface_levels(build)
        off, sag = mesh_deviation(build.surfaces[0].tube.axis, levels, vertices, triangles, level, min(build.radii))
        out["max_vertex_deviation"], out["max_triangle_deviation"] = off, sag
        if deflection is not None and off > deflection:
            raise FileAccuracyError(
                f"{target.name}: {fmt.upper()} holds the vertices only to {off:.2g} at this size, "
                f"above the mesh deflection {deflection:g}; use STEP or BREP"
            )
        if deflection is not None and sag > deflection + off:
            raise FileAccuracyError(
                f"{target.name}: {fmt.upper()} triangles lie up to {sag:.2g} from the tube, above "
                f"the mesh deflection {deflection:g} (+ {off:.1g} for the file's floats)"
            )
    return out


def _first_solids(shape: TopoDS_Shape, n: int) -> TopoDS_Compound:
    """A compound of the first ``n`` solids of ``shape``, in file order."""
    from OCP.BRep import BRep_Builder
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS_Compound

    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    explorer = TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More() and n > 0:
        builder.Add(compound, explorer.Current())
        n -= 1
        explorer.Next()
    return compound


def picture_report(path: Path, fmt: str, build: Any) -> dict[str, Any]:
    """A just-written picture of a tube's ``build`` read back (:func:`picture_pixels`), with
    the rings and stringers it draws."""
    layout, closed = build.layout, int(bool(build.surfaces[0].tube.axis.closed))  # a loop's last ring is its first
    return {
        **picture_pixels(path, fmt),
        "rings": len(layout.s_rings) - closed,
        "stringers": len(layout.stringers_deg),
    }


def picture_pixels(path: Path, fmt: str) -> dict[str, Any]:
    """A just-written picture read back: a PNG decoded to its pixels (width x height), an SVG
    parsed as XML with an <svg> root; raises if it is neither, so it is never moved into place."""
    path = Path(path)
    if fmt == "png":
        from matplotlib.image import imread

        height, width = imread(path, format="png").shape[:2]
        picture = f"PNG {width} x {height}"
    else:
        from xml.etree import ElementTree

        root = ElementTree.parse(path).getroot()
        if not root.tag.endswith("svg"):
            raise ExportError(f"{path.name}: not an SVG picture (root <{root.tag}>)")
        picture = f"SVG {root.get('width')} x {root.get('height')}"
    return {"bytes": path.stat().st_size, "picture": picture}
