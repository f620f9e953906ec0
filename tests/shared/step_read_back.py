"""A shape written to STEP by build123d and read back, for the tests that check what another
program (OCCT's reader, then its checks) makes of the file."""

from __future__ import annotations

from pathlib import Path

import build123d as bd


def step_read_back(shape: bd.Shape, path: Path) -> bd.Shape:
    """``shape`` written to ``path`` (STEP) and read back."""
    bd.export_step(shape, str(path))
    return bd.import_step(str(path))
