"""``tubecad mesh`` and ``tubecad analyse``: from a checked spec to the finite-element model
(tubecad.fem) and its files. No B-rep is built: the mesh is made on the exact surface."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.core.errors import ParameterError, SpecError
from tubecad.design.stages import stage
from tubecad.spec.design import design_class, design_of, spec_errors
from tubecad.spec.parse import AnySpec, TubeSpec, tube_spec
from tubecad.spec.sections import spec_error

if TYPE_CHECKING:
    from tubecad.design.model import Design
    from tubecad.design.shell import ShellModel


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


def mesh_from_spec(spec: AnySpec, **overrides: Any):
    """The spec's design meshed (:func:`fe_model`): its :class:`tubecad.fem.FEMesh`."""
    return fe_model(spec, **overrides).mesh


def fe_model(spec: AnySpec, **overrides: Any) -> ShellModel:
    """The spec's design (:func:`tubecad.spec.design.design_of`: a wall, a tube, a junction)
    as its shell model with the [mesh] settings (``overrides`` win: element, size, ...):
    shells on the net, [stiffeners] as beams, [panels] as sets, a junction's pads."""
    design = design_of(spec)
    settings = _mesh_settings(spec, overrides)
    if design.stiffeners is not None and settings.beams:
        _check_reach(tube_spec(spec, "tubecad mesh"), design.stiffeners, spec.wall, spec.source)
    if spec.analysis is not None:  # the ends the model takes, refused before it is meshed
        analysis_settings(
            spec, type(design), closed=spec.dispatch(lambda tube: bool(tube.tube.axis.closed), lambda _host: False)
        )
    with spec_errors(spec):
        return design.shell_model(settings)


def _mesh_settings(spec: AnySpec, overrides: dict[str, Any]):
    """The spec's checked [mesh] settings (``overrides`` win)."""
    from tubecad.spec.model import MeshSection

    try:
        return (spec.mesh or MeshSection()).settings(**overrides)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "mesh") from None


def analysis_settings(spec: AnySpec, kind: type[Design], closed: bool):
    """The spec's [analysis] settings (tubecad.fem.settings.analysis_settings) with the ends
    the design's model takes (:meth:`~tubecad.design.model.Design.analysis_ends`)."""
    from tubecad.spec.model import AnalysisSection

    try:
        settings = (spec.analysis or AnalysisSection()).settings(spec.length_unit, closed)
    except ParameterError as exc:
        raise SpecError(f"{spec.source}: {exc}", key=exc.key or "analysis") from None
    given = spec.analysis.ends if spec.analysis is not None else None
    with spec_errors(spec), stage("analysis"):
        return replace(settings, ends=kind.analysis_ends(given, settings.ends))


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


def material_and_step(spec: AnySpec, model: ShellModel, with_step: bool):
    """The [analysis] material and, if ``with_step``, the pressure step of the design's shell
    ``model`` (its own: :meth:`~tubecad.design.shell.ShellModel.pressure_step`), and the
    analysis settings."""
    from tubecad.core.units import length_unit, steel_density
    from tubecad.fem.inp import Material

    settings = analysis_settings(spec, design_class(spec), model.mesh.closed)
    # kg per cubic unit, in the mass unit that N and the length unit make consistent (kg m / unit: mm gives t)
    given = spec.stiffeners.density if spec.stiffeners is not None else None
    density = steel_density(spec.length_unit) if given is None else given
    density *= length_unit(spec.length_unit).metres
    material = Material(settings.youngs_modulus, settings.poisson_ratio, density)
    if not with_step:
        return material, None, settings
    with spec_errors(spec):
        return material, model.pressure_step(settings.pressure, settings.ends), settings


def write_mesh(spec: AnySpec, outputs: list[Path], **overrides: Any) -> tuple[Any, list[Path]]:
    """``tubecad mesh``: the mesh written to each output (by extension); a .inp gets the
    material and, when the spec has [analysis], its pressure step. A mesh a format cannot
    hold (a .inp of ``surface = 'both'``) is refused naming [mesh]."""
    outputs = checked_outputs(outputs)
    model = fe_model(spec, **overrides)
    mesh = model.mesh
    formats = _formats()
    material, step = None, None
    if any(p.suffix.lower() == ".inp" for p in outputs):
        if mesh.info["thickness"] is None:
            raise SpecError(f"{spec.source}: a .inp needs the wall's thickness: add a [wall] section", key="wall")
        material, step, _ = material_and_step(spec, model, spec.analysis is not None)
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


def analyse_spec(spec: AnySpec, output: Path, progress=None, **overrides: Any) -> dict[str, Any]:
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
    model = fe_model(spec, **overrides)
    mesh = model.mesh
    material, step, settings = material_and_step(spec, model, True)
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
        checks = model.checks(result.stress, result.ring_stress, settings.pressure)
        if checks is not None:
            summary["junction"] = checks
        write_text(staging / "results.json", json.dumps(summary, indent=2))
        for path in staging.iterdir():  # ccx's by-products (.dat, .sta, .cvg, ...) are not results
            if path.name not in summary["files"]:
                shutil.rmtree(path) if path.is_dir() else path.unlink()
    return summary
