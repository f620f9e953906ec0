"""The report of a build (report.json's content): the tube's parameters, exact measures and
measured checks, the B-rep measured, the stiffeners and lines."""

from __future__ import annotations

import json
from collections.abc import Sequence
from importlib.metadata import PackageNotFoundError, version
from typing import TYPE_CHECKING, Any

import numpy as np

from tubecad.core.grid import DEFAULT_NS, DEFAULT_NU
from tubecad.core.units import DEFAULT_LENGTH_UNIT, density_unit
from tubecad.surface import CanalSurface, CurvatureLineTube
from tubecad.surface.checks import area_by_quadrature, axis_distance_errors, net_errors
from tubecad.surface.protocol import CurvatureLineSurface

if TYPE_CHECKING:
    from tubecad.brep.solids import TubeBuild
    from tubecad.stiffeners.lines import CurvatureLine
    from tubecad.stiffeners.solids import Stiffener


def tube_report(
    tube: CurvatureLineSurface,
    nu: int = DEFAULT_NU,
    ns: int = DEFAULT_NS,
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> dict[str, Any]:
    """Exact measures (docs/MATH.md section 4) and what was measured on an ``nu`` x ``ns`` grid;
    lengths, areas and volumes are in ``length_unit`` (the spec's [units] length), as the
    report states. A canal surface (a radius law) gets :func:`canal_report`."""
    # the tube's closed forms (a constant law's canal surface as that tube), else the canal report
    return tube.dispatch(
        lambda exact: _tube_report(exact, nu, ns, length_unit),
        lambda exact: canal_report(exact, nu, ns, length_unit),
    )


def _tube_report(tube: CurvatureLineTube, nu: int, ns: int, length_unit: str) -> dict[str, Any]:
    """:func:`tube_report` of a tube: its exact measures (closed forms) and what was measured."""
    net = net_errors(tube, nu, ns)
    area = area_by_quadrature(tube)
    u = np.linspace(0.0, 2.0 * np.pi, 32, endpoint=False)[:, None]
    s = np.linspace(*tube.span, 201)[None, :]
    dist_err, s_err = axis_distance_errors(tube, u, s)
    reg = tube.regularity
    return {
        "tubecad_version": _version(),
        "units": {"length": length_unit},
        "parameters": {"axis": tube.axis.describe(), "tube": {"radius": tube.radius}},
        "length": tube.length,
        "area_exact": tube.area_exact,
        "volume_exact": tube.volume_exact,
        "area_numeric": area,
        "area_relative_error": abs(area / tube.area_exact - 1.0),
        "max_orthogonality_error": net.max_orthogonality_error,
        "max_M_error": net.max_M_error,
        "max_rho_k": reg.max_rho_k,
        "s_at_max_rho_k": reg.s_at_max_rho_k,
        "closest_axis_return": reg.closest_approach,
        "closest_axis_return_s": list(reg.closest_pair) if reg.closest_pair else None,
        "regular": reg.ok,
        "closed": tube.axis.closed,
        "holonomy_deg": float(np.degrees(tube.axis.holonomy)) if tube.axis.closed else None,
        "max_axis_distance_error": dist_err,
        "max_closest_axis_point_s_error": s_err,
        "grid": {"nu": net.nu, "ns": net.ns, "points": net.nu * net.ns},
        "definitions": {
            "max_orthogonality_error": "max |F|/sqrt(EG) over the grid: |cos| of the angle between isolines",
            "max_M_error": "max |M|/sqrt(EG) / sqrt((L/E)^2 + (N/G)^2): off-diagonal of the shape operator "
            "in the isoline frame relative to its norm",
            "area_numeric": "Gauss-Legendre (s) x periodic trapezoid (u) quadrature of |S_u x S_s|",
            "max_axis_distance_error": "max |distance to the closest axis point - rho| on a 32 x 201 grid",
            "holonomy_deg": "on a closed axis, the angle the rotation-minimising frame comes back turned by "
            "(r1(L) = cos h r1(0) + sin h r2(0)): the stringers meet the closing ring shifted by it",
        },
    }


def canal_report(
    surface: CanalSurface, nu: int = DEFAULT_NU, ns: int = DEFAULT_NS, length_unit: str = DEFAULT_LENGTH_UNIT
) -> dict[str, Any]:
    """The canal surface's report (docs/MATH.md section 8): its radius law (range, largest
    |r'|, where), regularity (the fold ratio, the smallest stringer speed, where), the net
    measured on an ``nu`` x ``ns`` grid, and area and volume two ways: by quadrature over
    the surface (divergence theorem for the volume) and from one-dimensional integrals of
    r(s), which share nothing but the law."""
    net = net_errors(surface, nu, ns)
    area, volume = surface.measures()
    area_swept, volume_swept = surface.swept_measures()
    reg = surface.regularity
    return {
        "tubecad_version": _version(),
        "units": {"length": length_unit},
        "parameters": {"axis": surface.axis.describe(), "tube": {"radius": surface.radius_law.describe()}},
        "surface": "canal",
        "length": surface.length,
        "area_numeric": area,
        "area_swept": area_swept,
        "area_relative_error": abs(area / area_swept - 1.0),
        "volume_numeric": volume,
        "volume_swept": volume_swept,
        "volume_relative_error": abs(volume / volume_swept - 1.0),
        "max_orthogonality_error": net.max_orthogonality_error,
        "max_M_error": net.max_M_error,
        "regularity": reg.describe(),
        "regular": reg.ok,
        "closed": surface.axis.closed,
        "grid": {"nu": net.nu, "ns": net.ns, "points": net.nu * net.ns},
        "definitions": {
            "max_orthogonality_error": "max |F|/sqrt(EG) over the grid: |cos| of the angle between isolines",
            "max_M_error": "max |M|/sqrt(EG) / sqrt((L/E)^2 + (N/G)^2): off-diagonal of the shape operator "
            "in the isoline frame relative to its norm",
            "area_numeric": "Gauss-Legendre (s) x periodic trapezoid (chi) quadrature of |X_chi x X_s|",
            "area_swept": "2 pi Int r (1 - r'^2 - r r'') ds",
            "volume_numeric": "1/3 of the flux of X through the surface and its two end discs",
            "volume_swept": "pi Int r^2 (1 - r'^2) (1 - r'^2 - r r'') ds: the characteristic discs swept along t",
            "max_fold": "max of r (k q + r'') / q^2, q = sqrt(1 - r'^2): the surface folds where it reaches 1",
        },
    }


def to_json(report: dict[str, Any]) -> str:
    """The report as report.json's text: indented JSON, no NaN or infinity (a strict reader's)."""
    return json.dumps(report, indent=2, allow_nan=False) + "\n"


def _version() -> str:
    try:
        return version("tubecad")
    except PackageNotFoundError:
        return "unknown"


def build_report(
    build: TubeBuild, tube: CurvatureLineSurface, nu: int = 48, ns: int = 1500, self_intersection: bool = False
) -> dict[str, Any]:
    """What was measured on a built B-rep shape (issue 3): per surface the fit's deviation
    and orthogonality by dense sampling of the OCCT surface, poles; topology and validity;
    OCCT's pre-boolean check (BOPAlgo_ArgumentAnalyzer: every check, the self-intersection
    test only with ``self_intersection``: ~1.5 s more on an 11 x 8 wall); volume and
    areas against the exact values (docs/MATH.md section 4): each surface's faces against
    its exact surface's area (:attr:`~tubecad.surface.CurvatureLineSurface.area_exact`: a
    tube's 2 pi rho L, a canal surface's or a wall's offset surface's by quadrature)."""
    # imported here so that `tubecad report` (maths only) never loads OCCT
    from tubecad.brep import properties as props
    from tubecad.brep.measure import face_orthogonality
    from tubecad.brep.solids import exact_volume
    from tubecad.fitting import measure_surface

    surfaces: list[dict[str, Any]] = []
    for surface, patches, radius in zip(build.surfaces, build.patches, build.radii):
        m = measure_surface(surface, nu, ns)
        faces = patches.all_faces()
        area = props.faces_area(faces)
        # the faces as built, edges and corners included: what a file read back is measured on
        # (tubecad.export.readback), so the build never reports better than its file
        orthogonality = max([m.max_orthogonality_error, *(face_orthogonality(f) for f in faces)])
        exact = surface.tube.area_exact  # the exact surface this one is fitted to (a wall's: its offset)
        surfaces.append(
            {
                "radius": radius,
                "poles": list(surface.pole_count),
                "pole_count": surface.pole_count[0] * surface.pole_count[1],
                "degree": [2, build.frame.degree],
                "max_deviation": m.max_deviation,
                "max_orthogonality_error": orthogonality,
                "samples": m.samples,
                "area": area,
                "area_exact": exact,
                "area_relative_error": abs(area / exact - 1.0),
            }
        )
    shape = build.shape
    is_solid = props.count(shape, "solid") > 0
    out: dict[str, Any] = {
        "kind": "wall" if len(build.radii) == 2 else ("tube_solid" if is_solid else "tube_shell"),
        "fit": {
            "method": f"exact-section NURBS (rational circles in u, degree-{build.frame.degree} B-spline in s)",
            "tolerance": build.tolerance,
            "max_deviation": max(s["max_deviation"] for s in surfaces),
            "max_orthogonality_error": max(s["max_orthogonality_error"] for s in surfaces),
        },
        "surfaces": surfaces,
        "layout": {"s_rings": list(build.layout.s_rings), "u_stringers_deg": list(build.layout.stringers_deg)},
        "faces": props.count(shape, "face"),
        "edges": props.count(shape, "edge"),
        "vertices": props.count(shape, "vertex"),
        "free_edges": props.free_edges(shape),
        "circle_edges": props.count_circle_edges(shape),
        "valid": props.is_valid(shape),
    }
    modes = tuple(m for m in props.ANALYZER_MODES if self_intersection or m != "SelfInterMode")
    out["boolean_check"] = {"checks": list(modes), "findings": props.analyzer_findings(shape, modes)}
    if is_solid:
        volume, exact = props.volume(shape), exact_volume(build, tube)
        out.update({"volume": volume, "volume_exact": exact, "volume_relative_error": abs(volume / exact - 1.0)})
    return out


def stiffener_report(
    stiffeners: Sequence[Stiffener],
    lines: Sequence[CurvatureLine],
    density: float,
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> dict[str, Any]:
    """Every curvature line (length) and stiffener (position, profile, length along its base
    line, volume, mass at ``density`` kg per cubic ``length_unit``), issue 4."""
    from tubecad.brep import properties as props

    out_lines = [
        {
            "name": ln.name,
            "kind": ln.kind,
            "surface_radius": ln.radius,
            ("s" if ln.kind == "ring" else "angle_deg"): ln.value,
            "length": ln.edge().length,
        }
        for ln in lines
    ]
    out_stiffeners = []
    for st in stiffeners:
        volume = props.volume(st.solid)
        out_stiffeners.append(
            {
                "name": st.name,
                "kind": st.kind,
                ("s" if st.kind == "ring" else "angle_deg"): st.value,
                "side": st.side,
                "profile": st.profile.kind,
                "height": st.profile.height,
                "thickness": st.profile.thickness,
                "base_radius": st.base_radius,
                "length": st.length(),
                "volume": volume,
                "mass_kg": volume * density,
                "valid": props.is_valid(st.solid),
            }
        )
    return {
        "density": density,
        "density_unit": density_unit(length_unit),
        "lines": out_lines,
        "stiffeners": out_stiffeners,
        "total_stiffener_mass_kg": sum(s["mass_kg"] for s in out_stiffeners),
    }
