"""The ``tubecad`` command line.

    tubecad paper [-o DIR]        the paper's example: pictures and report.json in DIR
    tubecad report SPEC.toml      print the report (JSON) of any spec

Bad input exits with code 2 and a one-line message naming the key or option.
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

from ..errors import TubecadError
from ..examples import paper_tube
from ..export.atomic import write_text
from ..export.plots import write_projections
from .report import DEFAULT_NS, DEFAULT_NU, to_json, tube_report
from .spec import load_spec


class UserError(click.ClickException):
    """Bad input: exit code 2, message only (no traceback)."""

    exit_code = 2


grid_options = [
    click.option("--nu", default=DEFAULT_NU, show_default=True, type=click.IntRange(8, 4096),
                 help="Grid points around the circle for the measured checks."),
    click.option("--ns", default=DEFAULT_NS, show_default=True, type=click.IntRange(8, 200_000),
                 help="Grid points along the axis for the measured checks."),
]  # fmt: skip


def with_grid_options(func):
    for option in reversed(grid_options):
        func = option(func)
    return func


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="tubecad")
def cli() -> None:
    """tubecad: tubular surfaces parameterised by their lines of curvature."""


@cli.command()
@click.option("-o", "--output", "output", default="tubecad-paper", show_default=True,
              type=click.Path(file_okay=False, path_type=Path), help="Folder to write into (created if needed).")
@with_grid_options
def paper(output: Path, nu: int, ns: int) -> None:
    """Build the paper's example (k = 10/s, beta = 10 deg, rho = 15, s in [200, 1200]).

    Writes projections.png/.svg (frontal and horizontal projections with the
    curvature-line net) and report.json into OUTPUT.
    """
    try:
        output.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UserError(f"cannot create output folder {str(output)!r}: {exc.strerror}") from None
    try:
        tube = paper_tube()
        written = write_projections(tube, output)
        written.append(write_text(output / "report.json", to_json(tube_report(tube, nu, ns))))
    except TubecadError as exc:
        raise UserError(str(exc)) from None
    for path in written:
        click.echo(str(path))


@cli.command()
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@with_grid_options
def report(spec: Path, nu: int, ns: int) -> None:
    """Print the JSON report of the tube described by SPEC (a TOML file)."""
    try:
        tube = load_spec(spec).tube
        click.echo(to_json(tube_report(tube, nu, ns)), nl=False)
    except TubecadError as exc:
        raise UserError(str(exc)) from None


def main() -> None:
    """Console-script entry point."""
    cli(prog_name="tubecad")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
