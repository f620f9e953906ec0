"""Spec files: the keys and their JSON Schema, parsing into the axis, surface and the typed
sections (:mod:`tubecad.spec.model`), building and exporting a spec, its report, and the
paper's sample spec. Library code a script can call without the command line::

    from tubecad.spec import build_and_export, load_spec

    spec = load_spec("samples/helix.toml")      # checked, its sections typed: spec.wall, spec.layout, ...
    report = build_and_export(spec, ["helix.step"])

Names are imported on first use, so ``tubecad schema`` (the keys alone) loads no numpy."""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "TubeSpec": "tubecad.spec.parse",
    "load_spec": "tubecad.spec.parse",
    "parse_spec": "tubecad.spec.parse",
    "read_spec_data": "tubecad.spec.parse",
    "SpecModel": "tubecad.spec.model",
    "StiffenerSelection": "tubecad.spec.model",
    "SpecBuild": "tubecad.spec.build",
    "build_from_spec": "tubecad.spec.build",
    "build_spec": "tubecad.spec.build",
    "export_build": "tubecad.spec.build",
    "build_and_export": "tubecad.spec.build",
    "tube_report": "tubecad.spec.report",
    "to_json": "tubecad.spec.report",
    "flat_from_spec": "tubecad.spec.outputs",
    "export_summary": "tubecad.spec.outputs",
    "render_step_picture": "tubecad.spec.outputs",
    "paper_spec": "tubecad.spec.paper",
    "write_paper": "tubecad.spec.paper",
    "spec_schema": "tubecad.spec.schema",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
