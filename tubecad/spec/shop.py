"""``tubecad shop``: from a checked spec to the shop package (tubecad.shop) in a folder.

Everything is written into a staging folder beside the output and moved into place only
once complete (:func:`tubecad.core.atomic.staged_folder`), so a failure (bad
``[fabrication]`` input, a plate too small for a piece) leaves no file behind."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from tubecad.spec.design import design_of, spec_errors
from tubecad.spec.parse import AnySpec


def shop_from_spec(spec: AnySpec, output: Path, progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """``tubecad shop``: the spec's design (a stiffened or paneled wall, a junction) made
    into its shop package with the ``[fabrication]`` settings
    (:meth:`~tubecad.design.model.Design.shop`) and written into ``output``; returns the
    index. Everything is written into a staging folder and moved into place once complete."""
    from tubecad.core.atomic import staged_folder
    from tubecad.spec.model import FabricationSection
    from tubecad.spec.preflight import check_shop

    check_shop(spec, output)
    fab = (spec.fabrication or FabricationSection()).settings(spec.length_unit)  # checked by check_shop
    design = design_of(spec)
    with spec_errors(spec):
        package = design.shop(fab, progress)
    with staged_folder(output) as staging:
        if progress is not None:
            progress("writing files")
        return package.write(staging, Path(str(spec.source)).stem)
