"""``tubecad shop``: from a checked spec to the shop package (tubecad.shop) in a folder.

Everything is written into a staging folder beside the output and moved into place only
once complete (:func:`tubecad.core.atomic.staged_folder`), so a failure (bad
``[fabrication]`` input, a plate too small for a piece) leaves no file behind."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from tubecad.core.errors import ParameterError
from tubecad.spec.parse import TubeSpec
from tubecad.spec.sections import spec_error


def shop_from_spec(spec: TubeSpec, output: Path, progress: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Build ``spec``'s wall, stiffeners and panels, compute the shop package with its
    ``[fabrication]`` settings and write it into ``output``; returns the index."""
    from tubecad.core.atomic import staged_folder
    from tubecad.shop.package import shop_data
    from tubecad.shop.writer import write_shop
    from tubecad.spec.build import build_from_spec, panels_from_spec, stiffeners_from_spec
    from tubecad.spec.model import FabricationSection
    from tubecad.spec.preflight import check_shop

    check_shop(spec, output)
    if spec.branches:  # a junction: the branches' cutting templates, openings and bevels
        from tubecad.spec.junction_shop import junction_shop

        return junction_shop(spec, output, progress)
    fab = (spec.fabrication or FabricationSection()).settings(spec.length_unit)  # checked by check_shop
    say = progress or (lambda _stage: None)
    say("building the wall")
    build = build_from_spec(spec)
    say("building stiffeners")
    stiffeners, _ = stiffeners_from_spec(spec, build)
    panels = panels_from_spec(spec, build)
    try:
        data = shop_data(build, stiffeners, panels, fab, say)
    except ParameterError as exc:  # a [fabrication] value the pieces cannot have (a plate too small, a joint)
        raise spec_error(spec.source, exc, ("fabrication",)) from None
    with staged_folder(output) as staging:
        say("writing files")
        index = write_shop(data, staging, Path(str(spec.source)).stem)
    return index
