"""The named, coloured tree of a tube in OCP CAD Viewer (ocp_vscode), issue 4.

``tubecad.show(...)`` and ``tubecad view SPEC`` send the named assembly of
tubecad.stiffeners.assembly (the same tree as the named STEP: ``wall`` or its panels,
``ring_XX`` and ``stringer_XX`` stiffeners, ``curvature_lines`` with ``line_ring_XX`` and
``line_stringer_XX``) to a running viewer: the VS Code extension "OCP CAD Viewer" or the
standalone one (``python -m ocp_viewer --port N``, the extra ``tubecad[viewer]``). The wall
is translucent so that inside stiffeners and the inner lines show; ring and stringer lines
have colours of their own.

The port is checked first, with a plain socket connect, so that a missing viewer is one
line (:class:`ViewerUnreachable`) before anything is imported or built. With
``OCP_VSCODE_PYTEST=1`` (ocp_vscode's test switch) nothing is sent and no viewer is needed:
:func:`show` returns what would have been sent (see :class:`Shown`).
"""

from __future__ import annotations

import contextlib
import os
import socket
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tubecad.core.errors import ParameterError, TubecadError

if TYPE_CHECKING:
    import build123d as bd


DEFAULT_PORT = 3939  # ocp_vscode's and ocp_viewer's default
DEFAULT_HOST = "127.0.0.1"
CONNECT_TIMEOUT = 0.5  # seconds; a closed local port answers at once, this bounds a silent host
WALL_ALPHA = 0.4
#: line colours: darker than the stiffeners' (RING_COLOUR, STRINGER_COLOUR), so they show on them
LINE_RING_RGB = (0.60, 0.18, 0.05)
LINE_STRINGER_RGB = (0.08, 0.25, 0.62)
PAPER = "paper"  # `tubecad view paper`, `show("paper")`: the paper's stiffened wall
RECORD_VARIABLES = ("OCP_VSCODE_PYTEST", "OCP_VIEWER_PYTEST")  # ocp_vscode's switch; its core's, since 4.x


class ViewerUnreachable(TubecadError, ConnectionError):
    """No viewer listens on the port: the message says how to start one."""


class NothingShown(TubecadError):
    """The viewer took the model but no browser page showed it: the message says how to open one."""


#: how long a browser page has, after a show, to report that it shows the model (s)
SHOWN_WITHIN = 10.0


@dataclass(frozen=True)
class Shown:
    """What :func:`show` sent: the trees (build123d Compounds), where to, and what
    ocp_vscode returned (with OCP_VSCODE_PYTEST=1, the tessellated data that would have
    been sent: ``((instances, shapes, config, count), mapping)``; else None)."""

    trees: tuple[Any, ...]
    host: str
    port: int
    sent: Any = None

    @property
    def recorded(self) -> bool:
        """True if nothing was sent (OCP_VSCODE_PYTEST=1): ``sent`` holds what would have been."""
        return self.sent is not None

    @property
    def names(self) -> list[str]:
        """Every label in the trees, depth first: wall, ring_01, ..., line_ring_00, ..."""
        out: list[str] = []

        def walk(node: Any) -> None:
            for child in getattr(node, "children", ()):
                out.append(child.label)
                walk(child)

        for tree in self.trees:
            walk(tree)
        return out

    def summary(self) -> str:
        """One line: what went where, e.g. ``paper: wall, 9 ring and 2 stringer stiffeners,
        38 curvature lines sent to the viewer on 127.0.0.1:3939``."""
        names = self.names
        count = lambda prefix: sum(n.startswith(prefix) for n in names)  # noqa: E731
        parts = [f"{count('panel_')} panels" if count("panel_") else ("net" if "net" in names else "wall")]
        if count("ring_") or count("stringer_"):
            parts.append(f"{count('ring_')} ring and {count('stringer_')} stringer stiffeners")
        if count("stiffener_"):  # a face's net: its webs on its lines
            parts.append(f"{count('stiffener_')} stiffeners")
        parts.append(f"{count('line_') + count('k1_') + count('k2_')} curvature lines")
        if count("umbilic_"):
            parts.append(f"{count('umbilic_')} umbilics")
        done = "recorded, not sent (OCP_VSCODE_PYTEST=1), for" if self.recorded else "sent to"
        labels = ", ".join(t.label for t in self.trees)
        return f"{labels}: {', '.join(parts)} {done} the viewer on {self.host}:{self.port}"


def recording() -> bool:
    """True when OCP_VSCODE_PYTEST (or ocp_viewer_core's OCP_VIEWER_PYTEST) is "1"."""
    return any(os.environ.get(name) == "1" for name in RECORD_VARIABLES)


def viewer_port(port: int | None = None) -> int:
    """``port``, else the environment's OCP_PORT (as ocp_vscode reads it), else 3939."""
    where = "port"
    if port is None:
        value = os.environ.get("OCP_PORT", "").strip()
        if not value:
            return DEFAULT_PORT
        where = "OCP_PORT"
        try:
            port = int(value)
        except ValueError:
            raise ParameterError(f"OCP_PORT must be a port number in [1, 65535], got {value!r}") from None
    if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
        raise ParameterError(f"{where} must be a port number in [1, 65535], got {port!r}")
    return port


def check_viewer(port: int, host: str = DEFAULT_HOST, timeout: float = CONNECT_TIMEOUT) -> None:
    """Raise :class:`ViewerUnreachable` unless something accepts connections on host:port."""
    try:
        with socket.create_connection((host, port), timeout=timeout):
            return
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
    raise ViewerUnreachable(
        f"no viewer on {host}:{port} ({reason}): open OCP CAD Viewer in VS Code, or start the standalone "
        f"one with `python -m ocp_viewer --port {port}` (pip install 'tubecad[viewer]'), or choose "
        f"another port (--port N, port=N or OCP_PORT)"
    )


def viewer_tree(
    item: Any,
    stiffeners: Sequence = (),
    panels: Sequence = (),
    lines: bool | Sequence = True,
    fuse: bool = False,
    wall_alpha: float = WALL_ALPHA,
) -> bd.Compound:
    """The styled named assembly of ``item``: a TubeBuild (with ``stiffeners``, ``panels`` and
    ``lines``: True for the layout's lines on every wall surface, False for none, or a list of
    CurvatureLine), a spec path (its [wall], [stiffeners] and [panels]), the word ``"paper"``
    (the wall, stiffeners and lines of `tubecad paper`), or a named assembly already built
    (whose colours are then changed in place)."""
    import build123d as bd

    from tubecad.brep import TubeBuild
    from tubecad.spec.build import wall_lines
    from tubecad.stiffeners.assembly import named_assembly

    if not 0.0 < wall_alpha <= 1.0:
        raise ParameterError(f"wall_alpha must be in (0, 1], got {wall_alpha!r}")
    if not isinstance(item, TubeBuild) and (stiffeners or panels or fuse or lines is not True):
        raise ParameterError(
            "stiffeners, panels, lines and fuse go with a TubeBuild; a spec has its own "
            "[stiffeners] and [panels], a named assembly its parts"
        )
    if isinstance(item, bd.Compound):
        tree = item
    elif isinstance(item, TubeBuild):
        chosen = wall_lines(item) if lines is True else list(lines or [])
        tree = named_assembly(item, stiffeners, chosen, fuse=fuse, panels=panels)
    elif isinstance(item, (str, Path)):
        tree = paper_tree() if str(item) == PAPER and not Path(item).exists() else spec_tree(item)
    else:
        raise ParameterError(
            f"show takes a TubeBuild, a spec path, {PAPER!r} or a named assembly, got {type(item).__name__}"
        )
    return style(tree, wall_alpha)


def spec_tree(path: str | Path) -> bd.Compound:
    """The named assembly `tubecad build` writes for a spec: a tube's with the lines on every
    wall surface; a [host] face's net with its lines, webs and umbilics."""
    from tubecad.spec.parse import load_spec

    tree = load_spec(path).dispatch(_tube_tree, _net_tree)
    tree.label = Path(path).stem
    return tree


def _tube_tree(spec: Any) -> bd.Compound:
    from tubecad.spec.build import build_from_spec, panels_from_spec, stiffeners_from_spec, wall_lines
    from tubecad.stiffeners.assembly import named_assembly

    build = build_from_spec(spec)
    stiffeners, selection = stiffeners_from_spec(spec, build)
    return named_assembly(
        build,
        stiffeners,
        wall_lines(build),
        fuse=bool(selection and selection.fuse),
        panels=panels_from_spec(spec, build),
    )


def _net_tree(spec: Any) -> bd.Compound:
    from tubecad.spec.design import net_design, spec_errors

    design = net_design(spec)
    with spec_errors(spec):
        return design.build_net().shape


def paper_tree() -> bd.Compound:
    """The paper's stiffened wall, as in paper_stiffened.step (`tubecad paper`)."""
    from tubecad.spec.build import wall_lines
    from tubecad.spec.paper import paper_stiffeners, paper_wall
    from tubecad.stiffeners.assembly import named_assembly

    build = paper_wall()
    tree = named_assembly(build, paper_stiffeners(build), wall_lines(build))
    tree.label = PAPER
    return tree


def style(tree: bd.Compound, wall_alpha: float = WALL_ALPHA) -> bd.Compound:
    """Viewer colours on a named assembly, in place: the wall (and every panel; a face's net)
    at ``wall_alpha``, ring and stringer lines (k1 and k2 lines) in colours of their own."""
    import build123d as bd

    from tubecad.stiffeners.assembly import WALL_COLOUR

    for child in tree.children:
        if child.label in ("wall", "net"):  # a tube's wall, a face's net or its wall
            for node in (child, *child.children):  # the panels, if any
                red, green, blue = tuple(node.color or WALL_COLOUR)[:3]
                node.color = bd.Color(red, green, blue, wall_alpha)
        elif child.label in ("curvature_lines", "lines"):  # a tube's lines, a face's net's
            for edge in child.children:
                rgb = LINE_RING_RGB if edge.label.startswith(("line_ring_", "k1_")) else LINE_STRINGER_RGB
                edge.color = bd.Color(*rgb)
    return tree


@contextlib.contextmanager
def _recorded() -> Iterator[None]:
    """ocp_vscode 4's show records instead of sending under its core's OCP_VIEWER_PYTEST;
    OCP_VSCODE_PYTEST alone (the documented switch) no longer does, so set both for the call."""
    old = os.environ.get("OCP_VIEWER_PYTEST")
    os.environ["OCP_VIEWER_PYTEST"] = "1"
    try:
        yield
    finally:
        if old is None:
            os.environ.pop("OCP_VIEWER_PYTEST", None)
        else:
            os.environ["OCP_VIEWER_PYTEST"] = old


def show(
    *items: Any,
    port: int | None = None,
    host: str = DEFAULT_HOST,
    stiffeners: Sequence = (),
    panels: Sequence = (),
    lines: bool | Sequence = True,
    fuse: bool = False,
    wall_alpha: float = WALL_ALPHA,
    **viewer_options: Any,
) -> Shown:
    """Send the named, coloured tree of each item (see :func:`viewer_tree`) to OCP CAD Viewer
    on ``host``:``port`` (default: OCP_PORT, else 3939). The port is checked before anything
    is built: :class:`ViewerUnreachable` if nothing listens. ``viewer_options`` go to
    ``ocp_vscode.show`` (defaults: ``reset_camera=Camera.RESET``, so the model is framed, and
    ``progress=""``, no tessellation marks on stdout).

    Args:
        *items: what to show, at least one, each a tree of its own: a
            :class:`~tubecad.brep.TubeBuild`, a spec file path (its [wall], [stiffeners] and
            [panels]), the word ``"paper"`` (the paper's stiffened wall, as ``tubecad
            paper``), or a named build123d assembly (restyled in place).
        port: the viewer's port, 1 to 65535; None (default): the environment's OCP_PORT,
            else 3939.
        host: the viewer's host (default ``"127.0.0.1"``).
        stiffeners: with a TubeBuild, its stiffeners (:class:`~tubecad.stiffeners.solids.Stiffener`
            objects) to show as solids (default none).
        panels: with a TubeBuild, its panels, shown as the wall's parts (default none: the
            wall as one solid).
        lines: with a TubeBuild, the curvature lines: True (default) the layout's lines on
            every wall surface, False none, or a list of ``CurvatureLine``.
        fuse: with a TubeBuild, the stiffeners fused into the wall as one solid (default
            False; not with ``panels``).
        wall_alpha: the wall's opacity, in (0, 1] (default 0.4: inside stiffeners and lines
            show through).
        **viewer_options: passed on to ``ocp_vscode.show``.

    Returns:
        A :class:`Shown`: the trees sent, the host and port, and (with OCP_VSCODE_PYTEST=1,
        nothing sent) what would have been sent.

    Raises:
        ParameterError: no items, an item of another kind, a bad ``port`` or
            ``wall_alpha``, or ``stiffeners``, ``panels``, ``lines`` or ``fuse`` given with
            an item that is not a TubeBuild.
        ViewerUnreachable: nothing listens on ``host``:``port`` (checked before anything is
            built; the message says how to start a viewer).
        NothingShown: the viewer took the model but no browser page showed it.
        SpecError: a spec path that cannot be read or built.
    """
    if not items:
        raise ParameterError("show needs something to show: a TubeBuild, a spec path or 'paper'")
    port = viewer_port(port)
    record = recording()
    if not record:
        check_viewer(port, host)
    try:
        import ocp_vscode
    except ImportError as exc:  # a dependency of tubecad: only a broken install lacks it
        raise TubecadError(f"the viewer client is missing ({exc}): pip install 'ocp_vscode>=4.2'") from None
    trees = tuple(viewer_tree(item, stiffeners, panels, lines, fuse, wall_alpha) for item in items)
    viewer_options.setdefault("reset_camera", ocp_vscode.Camera.RESET)
    viewer_options.setdefault("progress", "")
    ocp_vscode.set_port(port, host)  # pinned: no discovery, no prompt when several viewers run
    with _recorded() if record else contextlib.nullcontext():
        sent = ocp_vscode.show(*trees, names=[t.label for t in trees], port=port, **viewer_options)
    if not record:
        _check_shown(ocp_vscode, port, host, [t.label for t in trees])
    return Shown(trees, host, port, sent if record else None)


def _check_shown(ocp_vscode: Any, port: int, host: str, labels: list[str], within: float = SHOWN_WITHIN) -> None:
    """Wait until the viewer's page reports the tree it shows (its status holds a state per
    object, keyed by path: /paper/wall/...) and that tree is ours; else :class:`NothingShown`.
    The standalone viewer takes a model with no page open and only logs "No browser
    registered", so what was sent is not what was shown until the page says so."""
    deadline = time.monotonic() + within
    while True:
        states = (ocp_vscode.status(port=port) or {}).get("states") or {}
        if any(label in path.split("/") for path in states for label in labels):
            return
        if time.monotonic() > deadline:
            raise NothingShown(
                f"the viewer on {host}:{port} took the model, but no browser page shows it: open "
                f"http://{host}:{port}/viewer (or reload it), then run this again"
            )
        time.sleep(0.2)
