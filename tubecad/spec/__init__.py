"""Spec files: the keys and their JSON Schema, parsing into the axis, surface, layout and
settings, building and exporting a spec, and its report. Library code a script can call
without the command line."""
