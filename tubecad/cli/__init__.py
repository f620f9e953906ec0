"""The ``tubecad`` command line: a click shell over :mod:`tubecad.spec`, :mod:`tubecad.batch`
and the pipeline, with no logic a script would need."""
