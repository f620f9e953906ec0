"""Read an exported file back and compare it with the shape that was written."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..brep import properties as props
from ..export.cad import import_shape


def readback_report(path: str | Path, written) -> dict[str, Any]:
    """Validity, counts, free edges, and volume/area relative to the written shape."""
    shape = import_shape(path)
    out: dict[str, Any] = {
        "bytes": Path(path).stat().st_size,
        "valid": props.is_valid(shape),
        "solids": props.count(shape, "solid"),
        "faces": props.count(shape, "face"),
        "edges": props.count(shape, "edge"),
        "free_edges": props.free_edges(shape),
        "area_relative_error": abs(props.area(shape) / props.area(written) - 1.0),
    }
    if props.count(written, "solid"):
        out["volume_relative_error"] = abs(props.volume(shape) / props.volume(written) - 1.0)
    return out
