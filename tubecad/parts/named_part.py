"""The base of tubecad's build123d parts (:class:`NamedSolidsPart`): named solids, placed
as build123d places any part, with their curvature lines as labelled wires.

Its solids are its build123d ``children``, labelled as ``tubecad build`` names them:
``wall`` (on a tube too, as there), then a stiffened wall's ``ring_03``, ``stringer_05``, a
junction's ``pad``, ... in each placed copy, under the part's own label (its class name). So
build123d's own ``export_step(part, "part.step")`` writes them as named products, as
:func:`tubecad.export.cad.export_named_step` does (without its colours); the curvature
lines are not in it (they are edges of the solids, not solids).
"""

from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING, Any, Protocol

import build123d as bd

from tubecad.parts.engine import NetEdges

if TYPE_CHECKING:
    from tubecad.brep.layout import NetLayout
    from tubecad.surface.protocol import CurvatureLineSurface


class PartEngine(Protocol):
    """What a part was built from, shared (not copied) by the part's copies: its exact
    ``surface`` (a junction's main tube's), its ``layout``, its ``net`` of named edges as
    indices into its wall solid's edge map, and its report."""

    surface: Any
    layout: Any
    net: NetEdges

    def report(self) -> dict[str, Any]:
        """What was measured on the part."""
        ...


class _Naming:
    """The part's shape its labelled children were last made of (None: never), and whether
    they are being made now. A copy of the part starts over: its children are made anew,
    of the copy's own shape."""

    def __init__(self) -> None:
        self.shape: Any = None
        self.busy = False

    def __deepcopy__(self, memo: dict) -> _Naming:
        return _Naming()


#: the ``children`` property of every build123d shape (anytree's NodeMixin's)
_NODE_CHILDREN: Any = next(vars(c)["children"] for c in bd.Compound.__mro__ if "children" in vars(c))
#: build123d's ``wrapped`` property
_SHAPE_WRAPPED: Any = vars(bd.Shape)["wrapped"]


class NamedSolidsPart(bd.BasePartObject):
    """The base of tubecad's build123d parts: a part made of named solids (the wall first,
    then stiffeners or pads), placed as build123d places any part, whose curvature lines
    ``rings`` and ``stringers`` are labelled wires of its own edges in every placed copy.
    ``_tubecad`` is what it was built from (a :class:`PartEngine`), shared by its copies."""

    _applies_to = [bd.BuildPart._tag]

    def __init__(
        self, engine: PartEngine, part: bd.Part | bd.Solid, rotation: bd.RotationLike, align: Any, mode: bd.Mode
    ) -> None:
        self._tubecad = engine
        super().__init__(part=part, rotation=rotation, align=align, mode=mode)
        self.label = self.label or type(self).__name__
        self._naming: _Naming | None = _Naming()

    #: the labels of the solids of one placed copy of the part, in order (the wall first)
    _solid_names: tuple[str, ...] = ("wall",)

    @property
    def _solids_per_copy(self) -> int:
        """How many solids one placed copy of the part holds."""
        return len(self._solid_names)

    def _get_children(self) -> tuple[bd.Shape, ...]:
        self._name_solids()
        return _NODE_CHILDREN.fget(self)

    def _set_children(self, children: Any) -> None:
        naming = self.__dict__.get("_naming")
        if naming is not None and not naming.busy:  # the caller's own children: kept as given
            self._naming = None
        _NODE_CHILDREN.fset(self, children)

    #: build123d's (anytree's) ``children``, kept to one labelled solid per solid of the part's
    #: shape, however that shape was set (placed, moved, copied): what ``export_step`` names
    children = property(_get_children, _set_children, _NODE_CHILDREN.fdel)

    def _get_wrapped(self) -> Any:
        self._name_solids()
        return _SHAPE_WRAPPED.fget(self)

    #: the OCCT shape: made the compound of the labelled children first, if it changed since
    #: (``export_step`` reads the part's shape before its children)
    wrapped = property(_get_wrapped, _SHAPE_WRAPPED.fset)

    def _name_solids(self) -> None:
        """Make the children anew if the part's shape is not the one they were made of: a
        solid each, as placed (the shape becomes the compound of them, the same solids)."""
        naming = self.__dict__.get("_naming")
        shape = self.__dict__.get("_wrapped")
        if naming is None or naming.busy or shape is None:
            return
        if naming.shape is not None and naming.shape.IsEqual(shape):
            return
        naming.busy = True
        try:
            solids = list(self.solids())
            names = self._solid_names
            if len(solids) % len(names):  # not the part's own solids any more: no names, no children
                solids = []
            for i, solid in enumerate(solids):
                solid.label = names[i % len(names)]
            _NODE_CHILDREN.fset(self, solids)
            if not solids:  # detaching the old children emptied the shape: it stays as it was
                self._wrapped = shape
        finally:
            naming.busy = False
        shape = _SHAPE_WRAPPED.fget(self)
        naming.shape = shape.Located(shape.Location())  # a handle of its own: Move() on the shape changes it

    def __deepcopy__(self, memo: dict) -> Any:
        # the children are made anew of the copy's shape, on first use: not copied too
        children = self.__dict__.get("_NodeMixin__children")
        if children is not None:
            memo[id(children)] = []
        return super().__deepcopy__(memo)

    def _copies(self) -> list[bd.Solid]:
        """The wall's solid in each placed copy of the part."""
        return list(self.solids())[:: self._solids_per_copy]

    @property
    def surface(self) -> CurvatureLineSurface:
        """The exact curvature-line surface (:class:`~tubecad.surface.CurvatureLineTube` or
        :class:`~tubecad.surface.canal.CanalSurface`) the faces were fitted to."""
        return self._tubecad.surface

    @property
    def layout(self) -> NetLayout:
        """The :class:`~tubecad.brep.NetLayout`: ring arc lengths and stringer angles."""
        return self._tubecad.layout

    @property
    def rings(self) -> bd.ShapeList[bd.Wire]:
        """The ring frames (s = const lines of curvature) on the outer surface: one closed wire
        per ring, labelled ``ring_00``, ``ring_01``, ...; N distinct rings on a closed axis."""
        return self._wires(self._net.rings)

    @property
    def stringers(self) -> bd.ShapeList[bd.Wire]:
        """The stringers (the other family of lines of curvature) on the outer surface, from
        the first ring to the last: ``stringer_00``, ``stringer_01``, ...: as many as asked for."""
        return self._wires(self._net.stringers)

    @property
    def report(self) -> dict[str, Any]:
        """What was measured on this part (computed on first use, about a second): the
        engine's report (:meth:`PartEngine.report`)."""
        return self._report

    @cached_property
    def _report(self) -> dict[str, Any]:
        return self._tubecad.report()

    @property
    def _net(self) -> NetEdges:
        return self._tubecad.net

    def _wires(self, lines: dict[str, list[int]]) -> bd.ShapeList[bd.Wire]:
        """One wire per line and per placed copy of the part, of the part's own edges."""
        from tubecad.occ_compat import as_edge
        from tubecad.parts.engine import edge_map_of

        out = []
        for copy in self._copies():
            edge_map = edge_map_of(copy.wrapped)
            for name, indices in lines.items():
                for wire in self._line_wires([bd.Edge(as_edge(edge_map.FindKey(i))) for i in indices]):
                    wire.label = name
                    out.append(wire)
        return bd.ShapeList(out)

    def assembly(self) -> bd.Compound:
        """The part with every name, as ``tubecad build`` writes it: its solids (``wall``, the
        stiffeners or pads) labelled, then ``curvature_lines``, a compound of its named lines
        (each a labelled wire or edge set: ``ring_03``, ``stringer_05``, ``ring_03_inner``,
        a junction's ``saddle_outer``, ...), in every placed copy. build123d's own
        ``export_step(part.assembly(), "part.step")`` keeps them all (``export_step(part, ...)``
        keeps the solids' names: the lines are edges of the solids, not parts of it).

        Returns:
            a new build123d Compound labelled as the part; the part itself is unchanged.
        """
        solids = []
        for child in self.children:
            solid = bd.Solid(child.wrapped)  # a node of its own: the part's children stay the part's
            solid.label = child.label
            solids.append(solid)
        lines = bd.Compound(label="curvature_lines", children=self._named_lines())
        return bd.Compound(label=self.label, children=[*solids, lines])

    def _named_lines(self) -> list[bd.Shape]:
        """The lines :meth:`assembly` writes, labelled: the rings and stringers."""
        return [*self.rings, *self.stringers]

    def _line_wires(self, edges: list[bd.Edge]) -> list[bd.Wire]:
        """A line's edges as wires: one (a line whose edges join end to end)."""
        return [bd.Wire(edges)]
