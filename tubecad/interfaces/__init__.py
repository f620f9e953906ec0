"""How users reach tubecad: spec files, the command line, reports."""
