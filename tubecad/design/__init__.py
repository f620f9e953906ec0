"""Design values and the one engine under the spec, the parts and the CadQuery plugin.

A design (:class:`WallDesign`, :class:`JunctionDesign`) says what is built; its ``build()``
makes a :class:`BuildResult` (solids, named edges, the shape its files are written from,
the report), which :func:`write_outputs` writes and reads back. Names are imported on first
use.
"""

from tubecad.core.lazy import lazy_exports

_PUBLIC = {
    "Design": "tubecad.design.model",
    "WallDesign": "tubecad.design.wall",
    "JunctionDesign": "tubecad.design.junction",
    "BranchDesign": "tubecad.design.model",
    "WallChoice": "tubecad.design.model",
    "StiffenerChoice": "tubecad.design.model",
    "PanelChoice": "tubecad.design.model",
    "PadChoice": "tubecad.design.model",
    "BuildResult": "tubecad.design.result",
    "write_outputs": "tubecad.design.result",
    "mesh_tolerances": "tubecad.design.result",
    "WallResult": "tubecad.design.wall",
    "JunctionResult": "tubecad.design.junction",
    "ShellModel": "tubecad.design.shell",
}

__all__ = list(_PUBLIC)
__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, globals())
