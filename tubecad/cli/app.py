"""The ``tubecad`` command line.

    tubecad paper [-o DIR]                    the paper's example: pictures, STEP, IGES, report.json
    tubecad report SPEC.toml                  print the report (JSON) of any spec
    tubecad build SPEC.toml -o OUT.step ...   build the spec's solid, write STEP/IGES/BREP
    tubecad build A.toml B.toml ... -d DIR    a batch on all cores: DIR/NAME.step, NAME.report.json, batch.json
    tubecad build SPEC.toml --sweep tube.radius=10,12,15 -d DIR     the spec for each value (a batch)
    tubecad build ... -d DIR --scheduler tcp://HOST:PORT            the batch on a Dask cluster; reruns resume
    tubecad flat SPEC.toml -o DIR             flat patterns of the spec's stiffener webs
    tubecad shop SPEC.toml -o DIR             shop-floor package: nested webs, flanges, bending, marking, panels, pin jigs
    tubecad mesh SPEC.toml -o model.inp ...   finite-element shells and beams on the curvature-line net (.inp, .msh, .vtu)
    tubecad analyse SPEC.toml -o DIR          the [analysis] pressure case solved with CalculiX: results.json, a picture
    tubecad schema [-o FILE]                  the JSON Schema of spec files, for editors
    tubecad view SPEC.toml | paper [--port N] the named, coloured tree in OCP CAD Viewer

Bad input exits with code 2 and a one-line message naming the key or option. A batch
(tubecad.batch.jobs) prints a line per finished job to stderr and exits with 2 if any
job failed, 130 on Ctrl-C.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

import click

from tubecad.cli.signals import interrupts_end_at_once
from tubecad.core.atomic import remove_temporaries, write_text
from tubecad.core.errors import TubecadError
from tubecad.export.formats import FORMAT_NAMES as BATCH_FORMATS
from tubecad.spec.grid import DEFAULT_NS, DEFAULT_NU

if TYPE_CHECKING:
    from tubecad.spec.parse import AnySpec, TubeSpec

# Every command imports what it runs (numpy/scipy, OCCT and build123d, matplotlib) when it
# runs, inside interrupts_end_at_once, so that ``tubecad --help`` starts in a fraction of a
# second and a Ctrl-C during those imports ends the process at once. The logic lives in the
# packages (tubecad.spec, tubecad.batch, ...): a script calls it without this module.

#: what a command that builds loads first (OCCT and build123d, matplotlib: seconds)
HEAVY_MODULES = (
    "tubecad.brep",
    "tubecad.export.plots",
    "tubecad.export.readback",
    "tubecad.spec.build",
    "tubecad.spec.parse",
    "tubecad.spec.report",
)


def _load() -> None:
    """The heavy imports, made by the first command that needs them, where a Ctrl-C ends the
    process at once (nothing is written yet), never a half-initialised import's traceback."""
    from importlib import import_module

    with interrupts_end_at_once():
        for name in HEAVY_MODULES:
            import_module(name)


class UserError(click.ClickException):
    """Bad input: exit code 2, message only (no traceback)."""

    exit_code = 2


def _checked_spec(path: Path) -> AnySpec:
    """SPEC read and checked before the CAD kernel is loaded (tubecad.spec.parse is light), so
    that a mistake in it is refused at once, not after the 3-6 s OCCT and build123d take."""
    from tubecad.spec.parse import load_spec

    try:
        with interrupts_end_at_once():  # nothing is written yet: a Ctrl-C in its imports ends here
            return load_spec(path)
    except TubecadError as exc:
        raise UserError(str(exc)) from None


grid_options = [
    click.option(
        "--nu",
        default=DEFAULT_NU,
        show_default=True,
        type=click.IntRange(8, 4096),
        help="Grid points around the circle for the measured checks.",
    ),
    click.option(
        "--ns",
        default=DEFAULT_NS,
        show_default=True,
        type=click.IntRange(8, 200_000),
        help="Grid points along the axis for the measured checks.",
    ),
]


def with_grid_options(func):
    for option in reversed(grid_options):
        func = option(func)
    return func


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="tubecad")
def cli() -> None:
    """tubecad: tubular surfaces parameterised by their lines of curvature."""


@cli.command()
@click.option(
    "-o",
    "--output",
    "output",
    default="tubecad-paper",
    show_default=True,
    type=click.Path(file_okay=False, path_type=Path),
    help="Folder to write into (created if needed).",
)
@with_grid_options
def paper(output: Path, nu: int, ns: int) -> None:
    """Build the paper's example (k = 10/s, beta = 10 deg, rho = 15, s in [200, 1200]).

    Writes into OUTPUT: projections.png/.svg (frontal and horizontal projections with
    the curvature-line net); paper.step and paper.iges, the wall solid (thickness 2,
    centred: radii 14 and 16) with 11 ring frames and 8 stringers as its edges;
    paper_step.png, a picture rendered from the STEP file read back; paper_stiffened.step,
    a named assembly (wall, ring_01..ring_09 and stringer_00 and _04 flat-bar
    stiffeners inside the wall, curvature_lines with line_ring_00.., line_stringer_00..
    and their _inner twins) and its picture paper_stiffened.png;
    paper_lines.csv/.json, the curvature lines as polylines with tangents and normals;
    report.json.
    """
    _load()
    with interrupts_end_at_once():
        from tubecad.spec.paper import write_paper
    try:
        written = write_paper(output, nu, ns)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    for path in written:
        click.echo(str(path))
    _say_warnings(written)


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@with_grid_options
def report(spec: Path, nu: int, ns: int) -> None:
    """Print the JSON report of the tube described by SPEC (a TOML file); with [[branches]],
    the main tube's, and the branches as given (tubecad build --report measures the junction);
    with [host], the face's net built and measured (its umbilics, lines, patches, webs)."""
    checked = _checked_spec(spec)

    def of_tube(tube: TubeSpec) -> dict:
        with interrupts_end_at_once():  # numpy/scipy, never OCCT
            from tubecad.spec.report import tube_report
        measured = tube_report(tube.tube, nu, ns, tube.length_unit)
        if tube.branches:
            measured["branches"] = tube.sections["branches"]
            measured["junction"] = "not built here: tubecad build SPEC -o x.step --report r.json measures it"
        return measured

    def of_host(host) -> dict:
        _load()
        with interrupts_end_at_once():
            from tubecad.spec.outputs import net_report_from_spec
        return net_report_from_spec(host)

    try:
        measured = checked.dispatch(of_tube, of_host)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    from tubecad.spec.report import to_json

    click.echo(to_json(measured), nl=False)


@cli.command()
@click.option(
    "-o",
    "--output",
    "output",
    default=None,
    type=click.Path(dir_okay=False, path_type=Path),
    help="Write the schema to this file (atomically) instead of printing it.",
)
def schema(output: Path | None) -> None:
    """Print the JSON Schema (draft 2020-12) of spec files, for editors' completion and checks:
    e.g. tubecad schema -o tubecad-spec.schema.json, and "#:schema ./tubecad-spec.schema.json"
    as the first line of a spec (Even Better TOML / taplo). Made from the spec checker's own
    key tables; the checker stays the authority (it also checks the geometry)."""
    from tubecad.spec.schema import schema_text  # light: no numpy, no OCCT

    if output is None:
        click.echo(schema_text(), nl=False)
        return
    try:
        click.echo(str(write_text(output, schema_text())))
    except TubecadError as exc:
        raise UserError(str(exc)) from None


@cli.command()
@click.argument(
    "specs", metavar="SPEC [SPEC ...]", nargs=-1, required=True, type=click.Path(dir_okay=False, path_type=Path)
)
@click.option(
    "-o",
    "--output",
    "outputs",
    multiple=True,
    type=click.Path(dir_okay=False, path_type=Path),
    help="One SPEC: output file, repeatable; the format follows the extension: .step/.stp, .iges/.igs, "
    ".brep (exact B-rep), .stl, .3mf, .gltf/.glb (meshes for visual use), .csv/.json for the "
    "curvature lines as polylines (position, tangent, normal), or .png/.svg for the projections with the net.",
)
@click.option("--step-schema", type=click.Choice(["AP214", "AP242"]), default="AP214", show_default=True)
@click.option(
    "--report",
    "report_path",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="One SPEC: also write the measured report (JSON) here.",
)
@click.option(
    "-d",
    "--out-dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Batch: folder for NAME.EXT per format, NAME.report.json per job and batch.json (created if needed).",
)
@click.option(
    "-f",
    "--format",
    "formats",
    multiple=True,
    type=click.Choice(BATCH_FORMATS, case_sensitive=False),
    help="Batch: output format, repeatable (default step).",
)
@click.option(
    "--sweep",
    "sweeps",
    multiple=True,
    metavar="SECTION.KEY=VALUES",
    help="Batch: build each SPEC with KEY set to each value: 10,12,15 (TOML values) or START:STOP:COUNT "
    "(inclusive); several --sweep give every combination.",
)
@click.option(
    "-j",
    "--jobs",
    type=click.IntRange(min=1),
    default=None,
    help="Batch: jobs run at once, each in its own process  [default: all cores]",
)
@click.option(
    "--scheduler",
    default=None,
    metavar="tcp://HOST:PORT",
    help="Batch: run the jobs on this Dask distributed cluster (the extra tubecad[dask]; or [batch] "
    "scheduler in the first SPEC); results come back here. 'local': this machine's processes.",
)
@click.option(
    "--remote-dir",
    default=None,
    metavar="DIR",
    help="Batch on a cluster: the workers share a file system and write into DIR (the path of -d/--out-dir "
    "as the workers see it) instead of sending the files back.",
)
@click.option(
    "--resume",
    is_flag=True,
    help="Batch: skip the jobs whose outputs DIR/batch.json records as built from the same spec and "
    "unchanged (the default when DIR/batch.json exists).",
)
@click.option("--force", is_flag=True, help="Batch: build every job again, whatever DIR/batch.json records.")
@click.option(
    "--retries",
    type=click.IntRange(0, 100),
    default=1,
    show_default=True,
    help="Batch: how often a job is run again when its worker dies or it times out.",
)
@click.option(
    "--job-timeout",
    type=click.FloatRange(min=0, min_open=True),
    default=None,
    metavar="SECONDS",
    help="Batch: stop a job that runs longer (it is retried, then fails)  [default: no limit]",
)
@click.option(
    "--mesh-tolerance",
    type=float,
    default=None,
    metavar="LENGTH",
    help="Mesh outputs only (.stl, .3mf, .gltf, .glb): the farthest a triangle may lie from the surface, "
    "in model units, from 1e-4 to 1 x the smallest tube radius  [default: 1e-3 x that radius]",
)
@click.option(
    "--mesh-angle",
    type=float,
    default=None,
    metavar="DEGREES",
    help="Mesh outputs only: the most the normal may turn between neighbouring triangles, 1 to 45; the "
    "finer of the two tolerances wins  [default: 5.73 (0.1 rad)]",
)
@click.option(
    "-q",
    "--quiet",
    is_flag=True,
    help="No progress on stderr (shown once a build has run 2 s: a bar on a terminal, else lines); "
    "batch: no line per job.",
)
def build(
    specs: tuple[Path, ...],
    outputs: tuple[Path, ...],
    step_schema: str,
    report_path: Path | None,
    out_dir: Path | None,
    formats: tuple[str, ...],
    sweeps: tuple[str, ...],
    jobs: int | None,
    scheduler: str | None,
    remote_dir: str | None,
    resume: bool,
    force: bool,
    retries: int,
    job_timeout: float | None,
    mesh_tolerance: float | None,
    mesh_angle: float | None,
    quiet: bool,
) -> None:
    """Build the solid of SPEC (the wall if it has [wall], else the capped tube) and write it.

    With one SPEC and -o, each file is read back and checked; a summary is printed.

    Batch (several SPECs, --sweep or -d): every job writes DIR/NAME.EXT for each -f format and
    DIR/NAME.report.json, a line per finished job goes to stderr, DIR/batch.json lists every
    job; the exit code is 2 if any job failed.
    """
    one = not (len(specs) > 1 or sweeps or out_dir is not None)
    checked = _checked_spec(specs[0]) if one else None
    from tubecad.spec.preflight import check_build_outputs, check_mesh_options  # light: no OCCT

    try:
        check_mesh_options(outputs or [f"job.{f}" for f in formats or ("step",)], mesh_tolerance, mesh_angle)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    if resume and force:
        raise click.UsageError("--resume and --force exclude each other")
    if one and (formats or jobs is not None or scheduler or remote_dir or job_timeout is not None):
        raise click.UsageError(
            "-f/--format, -j/--jobs, --scheduler, --remote-dir and --job-timeout are for batch mode "
            "(several SPECs, --sweep, or -d/--out-dir)"
        )
    if one and not outputs:
        raise click.UsageError("Missing option '-o' / '--output' (or -d/--out-dir DIR for batch mode).")
    if checked is not None:  # what the spec and the options decide, before the 3-6 s of OCCT's imports
        try:
            check_build_outputs(checked, outputs, report_path, mesh_tolerance, mesh_angle)
        except TubecadError as exc:
            raise UserError(str(exc)) from None
    _load()
    with interrupts_end_at_once():
        from tubecad.core.progress import Progress
        from tubecad.spec.build import build_and_export
        from tubecad.spec.outputs import build_summary

    if not one:
        batch(
            specs,
            out_dir,
            outputs,
            report_path,
            formats=tuple(formats),
            sweeps=tuple(sweeps),
            step_schema=step_schema,
            jobs=jobs,
            mesh_tolerance=mesh_tolerance,
            mesh_angle=mesh_angle,
            scheduler=scheduler,
            remote_dir=remote_dir,
            resume=not force,
            retries=retries,
            job_timeout=job_timeout,
            quiet=quiet,
        )
        return
    assert checked is not None  # one SPEC, not a batch: read above
    written: list[Path] = []
    try:
        with Progress(enabled=not quiet) as progress:  # on stderr, once the build has run for 2 s
            report = build_and_export(
                checked, outputs, step_schema, report_path, written, mesh_tolerance, mesh_angle, progress
            )
    except TubecadError as exc:
        for path in written:  # a failed build (e.g. a file that cannot hold the tolerance) leaves no files
            path.unlink(missing_ok=True)
        raise UserError(str(exc)) from None
    for line in build_summary(report):
        click.echo(line)


def batch(specs, out_dir, outputs, report_path, **options) -> None:
    """``tubecad build`` over many specs or a sweep: :func:`tubecad.batch.runner.build_batch`
    with ``options`` (its :class:`~tubecad.batch.runner.BatchOptions`), its lines on
    stderr; exits 0, 2 (a job failed) or 130 (Ctrl-C)."""
    why = "several SPECs" if len(specs) > 1 else "--sweep" if options.get("sweeps") else "-d/--out-dir"
    if outputs or report_path is not None:
        raise click.UsageError(
            f"-o/--output and --report are for one SPEC; in batch mode ({why}) each job writes "
            f"DIR/NAME.EXT for each -f/--format and DIR/NAME.report.json into -d/--out-dir DIR"
        )
    if out_dir is None:
        raise click.UsageError(f"batch mode ({why}) needs -d/--out-dir DIR")
    with interrupts_end_at_once():
        from tubecad.batch.runner import BatchOptions, build_batch

    try:
        outcome = build_batch(specs, out_dir, BatchOptions(**options), lambda line: click.echo(line, err=True))
    except TubecadError as exc:
        if exc.key == "remote_dir":  # an option that needs another (--scheduler): a usage error
            raise click.UsageError(str(exc)) from None
        raise UserError(str(exc)) from None
    if outcome.exit_code:
        click.get_current_context().exit(outcome.exit_code)


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    "output",
    required=True,
    type=click.Path(file_okay=False, path_type=Path),
    help="Folder for webs.dxf, one SVG and PNG per web, and flat.json (created if needed).",
)
def flat(spec: Path, output: Path) -> None:
    """Flat patterns of the webs of SPEC's [stiffeners]: webs.dxf (all, [units] length), NAME.svg/.png
    each, and flat.json with every web's area and edge lengths (a tube's, or on a [host] face's
    net the webs on its lines)."""
    checked = _checked_spec(spec)
    from tubecad.spec.preflight import check_flat  # light: before OCCT loads

    try:
        check_flat(checked, output)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    _load()
    with interrupts_end_at_once():
        from tubecad.spec.outputs import flat_from_spec
    try:
        written = flat_from_spec(checked, output)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    for path in written:
        click.echo(str(path))
    _say_warnings(written)


def _say_warnings(written: list[Path]) -> None:
    """Every warning the written files record, one 'warning: ...' line each on stderr."""
    from tubecad.spec.outputs import written_warnings

    for warning in written_warnings(written):
        click.echo(f"warning: {warning}", err=True)


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    "output",
    required=True,
    type=click.Path(file_okay=False, path_type=Path),
    help="Folder for the package (created if needed): webs/, flanges/, bending/, marking/, panels/, "
    "pin_jig/, index.json and overview.png/.svg.",
)
@click.option("-q", "--quiet", is_flag=True, help="No stage lines on stderr (shown on a terminal only).")
def shop(spec: Path, output: Path, quiet: bool) -> None:
    """Shop-floor outputs of SPEC's stiffened wall, with its [fabrication] settings (plate_size, kerf,
    joint_gap, max_strain, pin_spacing, pin_clearance, joints); with [[branches]], each branch's
    cutting template, its opening's template and its bevel angles (branches/, index.json), and the
    webs of the stiffeners stopped at the openings:

    webs split at butt joints into cuttable pieces and nested 1:1 on plates (DXF, SVG) with the STEP
    solids split the same way; stringer flanges developed and nested; bending tables and inverse
    bending curves; each panel's marking lines (STEP), development with its strain (DXF, picture)
    and pin-jig heights (CSV, picture); index.json and a one-page overview. Nothing is written
    unless all of it is.
    """
    checked = _checked_spec(spec)
    from tubecad.spec.preflight import check_shop  # light: before OCCT loads

    try:
        check_shop(checked, output)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    _load()
    with interrupts_end_at_once():
        from tubecad.spec.shop import shop_from_spec

    live = not quiet and sys.stderr.isatty()  # stages on a terminal only: a log or a pipe gets the result lines
    say = (lambda stage: click.echo(stage, err=True)) if live else (lambda _stage: None)
    try:
        index = shop_from_spec(checked, output, say)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    if "lines" in index:  # a face's net: its webs
        webs = index["webs"]["nesting"]
        click.echo(
            f"webs: {webs['pieces']} pieces on {webs['plates']} plates, utilisation {100 * webs['utilisation']:.1f} %; "
            f"{len(index['lines'])} lines of curvature for marking"
        )
        jigs = index["panels"]
        if jigs:
            click.echo(
                f"panels: {len(jigs)} pin-jig tables, {sum(j['pins'] for j in jigs)} pins, "
                f"heights {min(j['heights'][0] for j in jigs):.4g} to {max(j['heights'][1] for j in jigs):.4g}"
            )
    elif "webs" in index:
        webs, flanges = index["webs"]["nesting"], index["flanges"]["nesting"]
        click.echo(
            f"webs: {webs['pieces']} pieces on {webs['plates']} plates, utilisation {100 * webs['utilisation']:.1f} %; "
            f"flanges: {flanges['pieces']} pieces on {flanges['plates']} plates; {len(index['bending'])} bending tables"
        )
    if "branches" in index:  # a junction: its templates and bevels
        for row in index["branches"]:
            dihedral, hole = row["dihedral_deg"], row["hole"]
            click.echo(
                f"branch {row['branch']}: cutting template {row['template']['girth']:.6g} x "
                f"{row['template']['height']:.6g} (strain {row['template']['strain']:.2g}), the opening's template "
                f"(on the main's {hole['developed']}, strain {hole['strain']:.2g}), "
                f"bevel basis: dihedral angle {dihedral['min']:.2f} to {dihedral['max']:.2f} deg"
            )
            if row["blend"] is not None:
                blend, strips = row["blend"], row["blend"]["strips"]
                worst = max(strip["max_strain"] for strip in strips)
                developing = sum(strip["develops"] for strip in strips)
                click.echo(
                    f"branch {row['branch']}: crotch blend (ball radius {blend['radius']:.6g}): its toes on the cutting "
                    f"template and the main's template, {len(strips)} strips developed, largest strain {worst:.3g} "
                    f"({developing} of {len(strips)} within max_strain; the rest are formed)"
                )
            if "files" not in index:
                for path in row["files"]:
                    click.echo(str(output / path))
        if "files" not in index:
            click.echo(str(output / "index.json"))
            return
    if index.get("panels") and "lines" not in index:  # a tube's panels, developed
        worst = max(index["panels"], key=lambda p: p["max_strain"])
        flagged = sum(p["exceeds_max_strain"] for p in index["panels"])
        click.echo(
            f"panels: {len(index['panels'])}, largest development strain {worst['max_strain']:.3g} "
            f"({worst['name']}), {flagged} above max_strain"
        )
    for warning in index["warnings"]:
        click.echo(f"warning: {warning}", err=True)
    for entry in index["files"]:
        click.echo(str(output / entry["path"]))
    click.echo(str(output / "index.json"))


#: a net's mesh with elements more elongated than this is said to be (tubecad mesh)
NET_ASPECT_WARNING = 20.0

_MESH_OPTIONS = [
    click.option(
        "--element",
        type=click.Choice(["S4", "S4R", "S8", "S8R"]),
        default=None,
        help="Shell element (overrides [mesh] element; default S8R).",
    ),
    click.option(
        "--size", type=float, default=None, help="Longest element edge both ways, model units (overrides [mesh] size)."
    ),
]


def _mesh_options(command):
    for option in reversed(_MESH_OPTIONS):
        command = option(command)
    return command


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    "outputs",
    multiple=True,
    required=True,
    type=click.Path(dir_okay=False, path_type=Path),
    help="Mesh file: .inp (CalculiX/Abaqus), .msh (gmsh 4.1) or .vtu (VTK); repeat for several.",
)
@_mesh_options
def mesh(spec: Path, outputs: tuple[Path, ...], element: str | None, size: float | None) -> None:
    """Finite-element mesh of SPEC's wall on its lines of curvature, with its [mesh] settings
    (element, beam, size, size_along, size_around, surface, max_elements, beams): quadrilateral
    shells (S4/S4R/S8/S8R) whose nodes lie on the exact surface with exact normals, element edges
    on the layout's rings and stringers, the [stiffeners] as beams (B31/B32) on the shells' nodes,
    and node and element sets named after the parts (ring_03, stringer_05, panel_r2_s1,
    start_ring, end_ring). A .inp also gets the material and, with [analysis], its pressure step.
    With [[branches]]: the junction's shell model (the walls' mid-surfaces joined on their saddle,
    meshed by gmsh; node sets saddle, pad, main_start, main_end, branch_end)."""
    checked = _checked_spec(spec)
    from tubecad.spec.mesh import checked_outputs  # light: the FE formats' table

    try:
        checked_outputs(list(outputs))
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    _load()
    with interrupts_end_at_once():
        from tubecad.spec.mesh import write_mesh

    try:
        built, written = write_mesh(checked, list(outputs), element=element, size=size)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    q = built.info["quality"]
    if built.info.get("kind") == "net":
        line = (
            f"{built.element_count} elements ({q['quads']} quads, {q['quads_on_curvature_lines']} of them on the "
            f"curvature lines, {q['triangles']} triangles), {len(built.nodes)} nodes, {len(built.beam_blocks)} beam "
            f"blocks; aspect ratio <= {q['aspect_ratio_max']:.3g}"
        )
        if q["aspect_ratio_max"] > NET_ASPECT_WARNING:
            click.echo(
                f"warning: elements up to aspect ratio {q['aspect_ratio_max']:.3g}: the net's lines end close to each "
                "other, to the face's corners or to a pole of its parameters; check the mesh before analysing it",
                err=True,
            )
    elif built.info.get("kind") == "junction":
        line = (
            f"{built.element_count} elements ({q['quads']} quads, {q['quads_on_curvature_lines']} of them on the "
            f"curvature lines, {q['triangles']} triangles), {len(built.nodes)} nodes, "
            f"{len(built.node_sets['saddle'])} on the saddle; aspect ratio <= {q['aspect_ratio_max']:.3g}"
        )
    else:
        line = (
            f"{built.element_count} elements ({built.info['elements_along']} along x {built.info['elements_around']} "
            f"around, {len(built.beam_blocks)} beam blocks), {len(built.nodes)} nodes; aspect ratio <= "
            f"{q['aspect_ratio_max']:.3g}, skew <= {q['skew_deg_max']:.3g} deg"
        )
    click.echo(line)
    for path in written:
        click.echo(str(path))


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    "output",
    required=True,
    type=click.Path(file_okay=False, path_type=Path),
    help="Folder for model.inp, model.frd, results.json and ring_stress.png (created if needed).",
)
@_mesh_options
@click.option("-q", "--quiet", is_flag=True, help="No stage lines on stderr (shown on a terminal only).")
def analyse(spec: Path, output: Path, element: str | None, size: float | None, quiet: bool) -> None:
    """Solve SPEC's [analysis] (internal pressure; ends fixed, capped or free) on its mesh with
    CalculiX (ccx), and write the deck, the results, a summary (results.json: displacements,
    stresses along the rings and stringers) and a picture of the ring stress on the deformed shell.
    With [[branches]]: the junction's hoop stress far from the saddle against membrane theory and
    the saddle's stress concentration, in results.json and on the terminal."""
    checked = _checked_spec(spec)
    from tubecad.spec.preflight import check_analysis  # light: [analysis], [wall] and ccx, before OCCT loads

    try:
        check_analysis(checked)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    _load()
    with interrupts_end_at_once():
        from tubecad.spec.mesh import analyse_spec

    live = not quiet and sys.stderr.isatty()
    say = (lambda stage: click.echo(stage, err=True)) if live else (lambda _stage: None)
    try:
        summary = analyse_spec(checked, output, say, element=element, size=size)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    ring, stringer = summary["ring_stress"], summary["stringer_stress"]
    click.echo(
        f"{summary['elements']} elements solved in {summary['solve_seconds']:.1f} s; ring stress "
        f"{ring['min']:.4g} to {ring['max']:.4g}, stringer stress {stringer['min']:.4g} to {stringer['max']:.4g}, "
        f"largest displacement {summary['max_displacement']:.4g}"
    )
    for line in junction_lines(summary.get("junction")):
        click.echo(line)
    for name in summary["files"]:
        click.echo(str(output / name))


def junction_lines(checks: dict | None) -> list[str]:
    """A junction's analysis on the terminal: the far-field hoop stress per tube against
    membrane theory and the saddle's stress concentration."""
    if not checks:
        return []
    lines = []
    for name, entry in checks["membrane"].items():
        if "hoop_expected_min" in entry:
            low, high = entry["hoop_expected_min"], entry["hoop_expected_max"]
            theory = f"{low:.4g}" if high - low <= 1e-9 * high else f"{low:.4g} to {high:.4g}"
            ring = entry["ring_mean_max_relative_error"]
            lines.append(
                f"{name}: hoop stress far from the saddle {entry['hoop_min']:.4g} to {entry['hoop_max']:.4g} "
                f"against membrane theory's {theory} ({entry['far_nodes']} nodes: within "
                f"{100 * entry['hoop_max_relative_error']:.2g} % at a node"
                + ("" if ring is None else f", {100 * ring:.2g} % round a ring")
                + ")"
            )
        else:
            lines.append(f"{name}: no node far enough from the saddle for the membrane check")
    saddle = checks["saddle"]
    lines.append(
        f"saddle: peak von Mises {saddle['peak_von_mises']:.4g}, {saddle['stress_concentration']:.3g} x the "
        f"main's hoop stress p R / t = {saddle['nominal_hoop']:.4g}"
    )
    return lines


@cli.command()
@click.argument("spec", metavar="SPEC")
@click.option(
    "--port", type=click.IntRange(1, 65535), default=None, help="Port of the viewer  [default: $OCP_PORT, else 3939]"
)
@click.option("--host", default="127.0.0.1", show_default=True, help="Host of the viewer.")
def view(spec: str, port: int | None, host: str) -> None:
    """Show SPEC (a TOML file, or the word paper for the paper's stiffened wall) in OCP CAD
    Viewer: wall (translucent, or its [panels]), ring_XX and stringer_XX stiffeners, and the
    curvature lines line_ring_XX, line_stringer_XX. Start a viewer first: the VS Code extension
    "OCP CAD Viewer", or python -m ocp_viewer --port N. Without one: exit code 2 at once."""
    from tubecad.integrations.viewer import show  # light; OCCT and ocp_vscode are imported after the port check

    try:
        shown = show(spec, port=port, host=host)
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    click.echo(shown.summary())


def main() -> None:
    """Console-script entry point.

    Ctrl-C and SIGTERM end a run cleanly: both raise KeyboardInterrupt, so every atomic write
    in progress removes its temporary file; one line "interrupted" goes to stderr and the
    exit code is 130. Click's own handling (usage errors, --help) is kept otherwise.
    """
    import signal

    def terminate(_signum, _frame):  # SIGTERM: the same clean exit as Ctrl-C
        raise KeyboardInterrupt

    try:
        signal.signal(signal.SIGTERM, terminate)
    except ValueError:  # pragma: no cover - not the main thread (embedded use)
        pass
    try:
        code = cli.main(prog_name="tubecad", standalone_mode=False)
    except click.exceptions.Abort as exc:
        if isinstance(exc.__cause__, KeyboardInterrupt):
            _interrupted()
        click.echo("Aborted!", err=True)
        sys.exit(1)
    except click.ClickException as exc:
        exc.show()
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        _interrupted()
    sys.exit(code if isinstance(code, int) else 0)


def _interrupted() -> None:
    from tubecad.cli.signals import INTERRUPTED_EXIT_CODE

    remove_temporaries()
    click.echo("interrupted", err=True)
    sys.exit(INTERRUPTED_EXIT_CODE)


if __name__ == "__main__":  # pragma: no cover
    main()  # it exits itself, with the run's exit code
