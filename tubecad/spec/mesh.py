"""``tubecad mesh`` and ``tubecad analyse``: from a checked spec to the finite-element model
(tubecad.fem) and its files. No B-rep is built: the mesh is made on the exact surface."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from tubecad.core.errors import ParameterError, RegularityError, SpecError
from tubecad.spec.parse import TubeSpec
from tubecad.spec.sections import spec_error

#: :func:`tubecad.fem.shell_mesh`'s parameters named otherwise than the spec's keys
SHELL_MESH_KEYS = {"thickness": "wall.thickness", "wall_side": "wall.side", "panel_rings": "panels.rings"}


#: the FE formats by extension (tubecad.fem.formats)
def _formats():
    from tubecad.fem.formats import FE_FORMATS

    return FE_FORMATS


def checked_outputs(outputs: list[Path]) -> list[Path]:
    """The outputs, each with an FE extension, or a SpecError naming the allowed ones."""
    formats = _formats()
    for path in outputs:
        if path.suffix.lower() not in formats:
            raise ParameterError(
                f"-o {path}: a mesh is written as {', '.join(formats)}, got {path.suffix or 'no extension'!r}"
            )
    return outputs


def mesh_from_spec(spec: TubeSpec, **overrides: Any):
    """The spec's wall (or tube) as an :class:`tubecad.fem.FEMesh` with its [mesh] settings
    (``overrides`` win: element, size, ...), [stiffeners] as beams and [panels] as sets."""
    from tubecad.fem import StiffenerPlan, shell_mesh

    if spec.branches:
        return _junction(spec, overrides).mesh
    source = spec.source
    settings = _mesh_settings(spec, overrides)
    tube = spec.tube
    try:
        layout = spec.layout.net(tube)
    except ParameterError as exc:  # parse_spec has checked it
        raise SpecError(f"{source}: [layout] {exc}", key=exc.key or "layout") from None
    wall = spec.wall
    plan = None
    if spec.stiffeners is not None:  # the section's one check, the build's too: profile, side, indices
        chosen = spec.stiffeners.select(layout, source, spec.length_unit)
        plan = StiffenerPlan(chosen.rings, chosen.stringers, chosen.profile, chosen.side)
        if settings.beams:
            _check_reach(spec, plan, wall, source)
    panels = spec.panels
    seams = rings = None
    if panels is not None:
        seams, rings = panels.seam_indices(len(layout.stringers_deg)), panels.ring_indices()
    try:
        return shell_mesh(
            tube,
            layout,
            thickness=None if wall is None else wall.thickness,
            wall_side="centered" if wall is None else wall.side,
            stiffeners=plan,
            seams=seams,
            panel_rings=rings,
            settings=settings,
            length_unit=spec.length_unit,
        )
    except (ParameterError, RegularityError) as exc:  # the mesh's own (its size, its surface), else a section's
        raise spec_error(source, exc, ("mesh", "stiffeners", "panels"), "mesh", SHELL_MESH_KEYS) from None


def _mesh_settings(spec: TubeSpec, overrides: dict[str, Any]):
    """The spec's checked [mesh] settings (``overrides`` win)."""
    from tubecad.spec.model import MeshSection

    try:
        return (spec.mesh or MeshSection()).settings(**overrides)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "mesh") from None


def _junction(spec: TubeSpec, overrides: dict[str, Any]):
    """A branched spec's shell model (tubecad.spec.junction_fem.JunctionModel)."""
    from tubecad.spec.junction_fem import junction_ends, junction_model

    if spec.analysis is not None:
        junction_ends(spec)  # refused before the mesh is made
    return junction_model(spec, _mesh_settings(spec, overrides))


def _fe_model(spec: TubeSpec, overrides: dict[str, Any]):
    """(the mesh, the junction's model or None)."""
    if spec.branches:
        model = _junction(spec, overrides)
        return model.mesh, model
    return mesh_from_spec(spec, **overrides), None


def _check_reach(spec: TubeSpec, plan, wall, source) -> None:
    """A stiffener too high for the wall's curvature is refused as the solids refuse it
    (tubecad.stiffeners.limits), naming [stiffeners] height."""
    from tubecad.stiffeners.limits import checked_reach

    tube = spec.tube.fast_path()  # a constant law: the tube of that radius
    if not tube.constant_radius:
        radius = tube.radius_law.min_radius
        if plan.side == "inside" and plan.profile.height >= radius:
            raise SpecError(
                f"{source}: [stiffeners] height must be < {radius:g} (the smallest radius) inside, "
                f"got {plan.profile.height:g}",
                key="stiffeners.height",
            )
        return
    radius = tube.radius_law.constant_value  # a constant radius: the tube's rho
    r_in, r_out = (radius, radius) if wall is None else wall.radii(radius)
    base = r_out if plan.side == "outside" else r_in
    try:
        for kind, chosen in (("ring", plan.rings), ("stringer", plan.stringers)):
            if chosen:
                checked_reach(tube.axis, plan.profile, base, plan.side, kind)
    except ParameterError as exc:
        raise SpecError(f"{source}: [stiffeners] {exc}", key="stiffeners.height") from None


def material_and_step(spec: TubeSpec, mesh, with_step: bool, junction=None):
    """The [analysis] material and, if ``with_step``, the pressure step (tubecad.fem.loads;
    a junction's, ``junction`` its model: tubecad.spec.junction_fem)."""
    from tubecad.core.units import length_unit, steel_density
    from tubecad.fem.inp import Material
    from tubecad.fem.loads import pressure_step
    from tubecad.spec.model import AnalysisSection

    try:
        settings = (spec.analysis or AnalysisSection()).settings(spec.length_unit, mesh.closed)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "analysis") from None
    # kg per cubic unit, in the mass unit that N and the length unit make consistent (kg m / unit: mm gives t)
    given = spec.stiffeners.density if spec.stiffeners is not None else None
    density = steel_density(spec.length_unit) if given is None else given
    density *= length_unit(spec.length_unit).metres
    material = Material(settings.youngs_modulus, settings.poisson_ratio, density)
    if not with_step:
        return material, None, settings
    if junction is not None:
        from tubecad.spec.junction_fem import junction_ends, junction_step

        settings = replace(settings, ends=junction_ends(spec))
        return material, junction_step(spec, junction, settings.pressure), settings
    surface = reference_surface(spec, mesh)
    ends = (mesh.node_sets.get("start_ring"), mesh.node_sets.get("end_ring"))
    try:
        step = pressure_step(mesh, settings.pressure, settings.ends, surface, ends)
    except ParameterError as exc:
        raise spec_error(spec.source, exc, ("analysis",), "analysis") from None
    return material, step, settings


def reference_surface(spec: TubeSpec, mesh):
    """The surface the mesh's (first) shells lie on."""
    d = mesh.info["reference_offsets"][0]
    return spec.tube if d == 0 else spec.tube.offset(d, allow_irregular=True)


def write_mesh(spec: TubeSpec, outputs: list[Path], **overrides: Any) -> tuple[Any, list[Path]]:
    """``tubecad mesh``: the mesh written to each output (by extension); a .inp gets the
    material and, when the spec has [analysis], its pressure step. A mesh a format cannot
    hold (a .inp of ``surface = 'both'``) is refused naming [mesh]."""
    outputs = checked_outputs(outputs)
    mesh, junction = _fe_model(spec, overrides)
    formats = _formats()
    material, step = None, None
    if any(p.suffix.lower() == ".inp" for p in outputs):
        if mesh.info["thickness"] is None:
            raise SpecError(f"{spec.source}: a .inp needs the wall's thickness: add a [wall] section", key="wall")
        material, step, _ = material_and_step(spec, mesh, spec.analysis is not None, junction)
    written = []
    for path in outputs:
        try:
            formats[path.suffix.lower()].write(
                mesh, path, material=material, step=step, title=Path(str(spec.source)).stem
            )
        except ParameterError as exc:
            raise spec_error(spec.source, exc, ("mesh",)) from None
        written.append(path)
    return mesh, written


def analyse_spec(spec: TubeSpec, output: Path, progress=None, **overrides: Any) -> dict[str, Any]:
    """``tubecad analyse``: the spec's mesh with its [analysis] pressure step solved by
    CalculiX; writes model.inp, model.frd, results.json and ring_stress.png into ``output``
    (through a staging folder, :func:`tubecad.core.atomic.staged_folder`: nothing is left
    unless all of it is written)."""
    import json
    import shutil

    from tubecad.core.atomic import staged_folder, write_text
    from tubecad.fem.analysis import solve
    from tubecad.fem.calculix import CalculixError
    from tubecad.fem.plot import save_deformed
    from tubecad.spec.preflight import check_analysis

    check_analysis(spec)
    say = progress or (lambda _stage: None)
    say("meshing")
    mesh, junction = _fe_model(spec, overrides)
    material, step, settings = material_and_step(spec, mesh, True, junction)
    with staged_folder(output) as staging:
        say(f"solving {mesh.element_count} elements with CalculiX")
        try:
            result = solve(mesh, material, step, staging, "model")
        except CalculixError as exc:
            raise SpecError(f"{spec.source}: {exc}") from None
        except ParameterError as exc:  # a mesh CalculiX cannot take (surface = 'both')
            raise spec_error(spec.source, exc, ("mesh",)) from None
        say("writing results")
        unit = spec.length_unit
        title = (
            f"{Path(str(spec.source)).stem}: stress along the rings, p = {settings.pressure:g} ({settings.ends} ends)"
        )
        save_deformed(result, result.ring_stress, f"ring stress (N/{unit}^2)", staging, "ring_stress", title)
        summary = {
            "spec": str(spec.source),
            "units": {"length": unit, "force": "N"},
            "analysis": {
                "pressure": settings.pressure,
                "ends": settings.ends,
                "youngs_modulus": settings.youngs_modulus,
                "poisson_ratio": settings.poisson_ratio,
            },
            "mesh": {k: v for k, v in mesh.info.items()},
            **result.summary(),
            "files": ["model.inp", "model.frd", "ring_stress.png", "results.json"],
        }
        if junction is not None:
            from tubecad.fem.junction_analysis import junction_checks

            summary["junction"] = junction_checks(
                mesh, junction.tubes, result.stress, result.ring_stress, settings.pressure
            )
        write_text(staging / "results.json", json.dumps(summary, indent=2))
        for path in staging.iterdir():  # ccx's by-products (.dat, .sta, .cvg, ...) are not results
            if path.name not in summary["files"]:
                shutil.rmtree(path) if path.is_dir() else path.unlink()
    return summary
