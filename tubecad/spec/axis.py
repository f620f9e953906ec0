"""The [axis] section of a spec: which kind of axis, built from its checked keys
(docs/spec-files.md; the keys are in :mod:`.spec_keys`).

Files named in the section (``points`` CSV, ``edge`` STEP/BREP) are found relative to the
spec's folder. Only the ``edge`` kind loads OCCT, to read its file.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.core.validation import span_pair
from tubecad.curves import FAMILIES, Axis

#: the most rows a points file may hold (the same bound as inline points)
MAX_FILE_BYTES = 50_000_000


def build_axis(curve: str, values: dict[str, Any], base: Path | None = None, length_unit: str = "mm") -> Axis:
    """The axis of kind ``curve`` from the section's checked ``values``; ``base``: the folder
    that relative file names start from."""
    if curve in FAMILIES:  # slope curves: (family keys, beta_deg, s)
        cls = FAMILIES[curve]
        span = span_pair("s", values["s"], cls.s_lower_bound)
        params = {k: v for k, v in values.items() if k not in ("curve", "beta_deg", "s")}
        return cls(beta_deg=values["beta_deg"], span=span, **params)
    if curve == "natural":
        from tubecad.curves.natural import NaturalAxis

        frame = {key: values[key] for key in ("origin", "tangent", "normal") if key in values}
        return NaturalAxis(
            values["k"], values["tau"], span_pair("s", values["s"]), **frame, closed=values.get("closed")
        )
    if curve == "parametric":
        from tubecad.curves.parametric import ParametricAxis, expression_curve

        description = {"curve": "parametric", **{key: values[key] for key in ("x", "y", "z")}, "t": list(values["t"])}
        return ParametricAxis(
            expression_curve(values["x"], values["y"], values["z"]),
            span_pair("t", values["t"]),
            normal=values.get("normal"),
            description=description,
            closed=values.get("closed"),
        )
    if curve == "points":
        from tubecad.curves.points import points_axis

        return points_axis(
            _points(values, base),
            parameterisation=values.get("parameterisation", "centripetal"),
            normal=values.get("normal"),
            closed=values.get("closed"),
        )
    if curve == "route":
        from tubecad.curves.route import RouteAxis

        return RouteAxis(
            _points(values, base), values["bend_radius"], normal=values.get("normal"), closed=values.get("closed")
        )
    if curve == "edge":
        from tubecad.curves.edge import edge_axis

        if values.get("index", 0) < 0:
            raise ParameterError(f"index must be >= 0 (wires first, then edges), got {values['index']}")
        path = _file(values["file"], base)
        shape, what = read_centreline(path, values.get("name"), values.get("index"), length_unit)
        return edge_axis(shape, normal=values.get("normal"), source=f"{path.name}: {what}", closed=values.get("closed"))
    raise ParameterError(f"curve {curve!r} is not a kind of axis")  # the key table keeps this unreachable


def _file(name: str, base: Path | None) -> Path:
    path = Path(name)
    if not path.is_absolute() and base is not None:
        path = base / path
    if not path.is_file():
        raise ParameterError(
            f"file {name!r} not found (looked for {str(path)!r}; relative names start at the spec's folder)"
        )
    return path


def _points(values: dict[str, Any], base: Path | None) -> np.ndarray:
    """The inline ``points``, or the rows of the CSV ``file`` (x, y, z; a header line is skipped)."""
    if ("points" in values) == ("file" in values):
        raise ParameterError('give either points = [[x, y, z], ...] or file = "points.csv", not both or neither')
    if "points" in values:
        return np.asarray(values["points"], dtype=float)
    path = _file(values["file"], base)
    if path.stat().st_size > MAX_FILE_BYTES:
        raise ParameterError(f"file {values['file']!r} is larger than {MAX_FILE_BYTES} bytes")
    rows: list[list[float]] = []
    with open(path, encoding="utf-8", errors="replace") as handle:
        for number, line in enumerate(handle, 1):
            fields = [f.strip() for f in line.replace(";", ",").split(",") if f.strip()]
            if not fields or fields[0].startswith("#"):
                continue
            try:
                row = [float(f) for f in fields]
            except ValueError:
                if not rows:  # a header
                    continue
                raise ParameterError(
                    f"file {values['file']!r} line {number}: not three numbers x, y, z: {line.strip()[:80]!r}"
                ) from None
            if len(row) != 3:
                raise ParameterError(f"file {values['file']!r} line {number}: {len(row)} numbers, expected x, y, z")
            rows.append(row)
    return np.asarray(rows, dtype=float).reshape(-1, 3)


def read_centreline(path: Path, name: str | None, index: int | None, length_unit: str) -> tuple[Any, str]:
    """The wire or edge of a STEP/BREP file the tube follows, and a few words on which:
    ``name`` (a STEP label), else ``index`` into wires then edges, else the only one."""
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_WIRE
    from OCP.TopExp import TopExp_Explorer

    from tubecad.core.errors import TubecadError
    from tubecad.export.cad import import_shape

    if name is not None:
        return _named(path, name, length_unit), f"{name!r}"
    try:
        shape = import_shape(path, length_unit)
    except TubecadError as exc:
        raise ParameterError(f"file: {exc}") from None
    found: dict[str, list] = {"wire": [], "edge": []}
    for kind, topabs in (("wire", TopAbs_WIRE), ("edge", TopAbs_EDGE)):
        explorer = TopExp_Explorer(shape, topabs)
        while explorer.More():
            found[kind].append(explorer.Current())
            explorer.Next()
    candidates = [("wire", i, s) for i, s in enumerate(found["wire"])] + [
        ("edge", i, s) for i, s in enumerate(found["edge"])
    ]
    if not candidates:
        raise ParameterError(f"file {path.name!r} holds no edge or wire to follow")
    if index is None:
        if len(found["wire"]) == 1 or (not found["wire"] and len(found["edge"]) == 1):
            kind, i, chosen = candidates[0]
            return chosen, f"{kind} {i}"
        raise ParameterError(
            f"file {path.name!r} holds {len(found['wire'])} wires and {len(found['edge'])} edges: "
            f"pick one with index (0 to {len(candidates) - 1}, wires first) or name"
        )
    if index >= len(candidates):
        raise ParameterError(f"index must be in 0 to {len(candidates) - 1} (wires first, then edges), got {index}")
    kind, i, chosen = candidates[index]
    return chosen, f"{kind} {i}"


def _named(path: Path, name: str, length_unit: str) -> Any:
    """The shape labelled ``name`` in a STEP file (build123d reads the labels, in mm)."""
    import build123d as bd

    from tubecad.core.units import length_unit as unit

    try:
        root = bd.import_step(str(path))
    except Exception as exc:  # whatever the reader says, as one line
        raise ParameterError(f"file {path.name!r} cannot be read as STEP: {exc}"[:300]) from None
    stack, labels = [root], []
    while stack:
        node = stack.pop()
        labels.append(node.label)
        if node.label == name:
            pieces = node.wires() or node.edges()
            if not pieces:
                raise ParameterError(f"name {name!r}: that part of {path.name!r} holds no edge or wire")
            scale = 1.0 / unit(length_unit).mm
            return pieces[0].scale(scale) if scale != 1.0 else pieces[0]
        stack.extend(getattr(node, "children", ()))
    known = ", ".join(repr(label) for label in labels if label)[:200]
    raise ParameterError(f"name {name!r} is not in {path.name!r} (its names: {known or 'none'})")
