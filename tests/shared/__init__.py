"""What two test files share (spec texts, helpers, fixtures), one module per area: a unit test
file and the tests/e2e/test_cli_*.py file that drives the same thing from the command line
import it from here (tests/ is on sys.path, as for ``from conftest import ROOT``).

A fixture is defined here with ``name=`` and imported under its function's name,
``from shared.junction_fem import tee_fixture as tee_fixture``: pytest finds it as an attribute
of the test module and makes it that module's own, at the scope it is defined with; the
redundant ``as`` marks the import as used (ruff's F401), and the other name keeps the tests'
arguments from redefining the import (F811)."""
