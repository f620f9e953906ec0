"""``CurvatureNet``: a face the user already has, thickened into a wall whose lines of
curvature are its edges, as a build123d part (issue 44).

The same design a ``[host]`` spec makes (:class:`~tubecad.design.net.NetDesign`), built the
same way; usable in builder mode (``mode``, ``rotation``, ``align``, inside ``Locations``)
and in algebra mode like build123d's own parts::

    import build123d as bd
    from tubecad import CurvatureNet

    face = bd.Face.make_surface_from_array_of_points(
        [[(x, y, 0.002 * x * x - 0.001 * y * y + 0.0005 * x * y) for y in (0, 50, 100, 150)] for x in (0, 50, 100, 150)]
    )
    net = CurvatureNet(face, k1_lines=3, k2_lines=3, thickness=2.0)
    assert [line.label for line in net.k1] == ["k1_00", "k1_01", "k1_02"]
    assert net.report["net"]["angle"] < 1e-8  # the edges follow the principal directions

Its solids are its build123d ``children``: ``wall``, then each web (``stiffener_k1_03``...),
so ``export_step(net, ...)`` names them; :meth:`CurvatureNet.assembly` adds the lines
(``k1_03``...) and the umbilics (``umbilic_0``...), as ``tubecad build`` writes them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cached_property
from typing import Any

import build123d as bd

from tubecad.brep.wall import WallSide
from tubecad.design.net import DEFAULT_LINES, LineSelection, NetDesign, PatchSurfaces
from tubecad.stiffeners.profiles import Profile, StiffenerSide


class CurvatureNet(bd.BasePartObject):
    """A face's curvature-line net as a wall of ``thickness`` (module docstring).

    Args:
        face: a build123d ``Face`` (or an OCCT ``TopoDS_Face``): B-spline, NURBS or analytic,
            trimmed or not.
        k1_lines: lines of family 1 (along the k1 direction), 1 .. 200.
        k2_lines: lines of family 2.
        thickness: the wall's thickness (> 0).
        side: where the wall lies from the face: ``centered``, ``inside`` (against its normal)
            or ``outside``.
        k1_spacing: instead of ``k1_lines``, the distance between neighbouring k1 lines along
            the k2 line through the seed.
        k2_spacing: the same for the k2 lines.
        seed: a point (x, y, z) of the face: each family's lines are spread along the other
            family's line through it.
        stiffened: webs on the net's lines: ``{"k1": [1, 3], "k2": "all"}``.
        profile: the stiffeners' profile (``Profile("flat", height, thickness)``, a T or an L).
        stiffener_side: ``outside`` (along the face's normal) or ``inside``.
        patches: the cells' surfaces: ``host`` (the face's own, split by the lines) or
            ``curvature`` (each four-sided cell refitted as a patch whose isolines are its
            lines of curvature; ``report["patches"]`` gives each patch's figures and the
            cells kept on the face).
        rotation: build123d's part rotation.
        align: build123d's part alignment.
        mode: build123d's combine mode in builder mode.

    Raises:
        ParameterError: naming the argument (``k1_lines``, ``seed``, ``face``, ``thickness``,
            ``k1``...).
    """

    _applies_to = [bd.BuildPart._tag]

    def __init__(
        self,
        face: Any,
        k1_lines: int | None = DEFAULT_LINES,
        k2_lines: int | None = DEFAULT_LINES,
        *,
        thickness: float,
        side: WallSide = "centered",
        k1_spacing: float | None = None,
        k2_spacing: float | None = None,
        seed: Sequence[float] | None = None,
        stiffened: Mapping[str, LineSelection | Sequence[int]] | None = None,
        profile: Profile | None = None,
        stiffener_side: StiffenerSide = "outside",
        patches: PatchSurfaces = "host",
        rotation: bd.RotationLike = (0, 0, 0),
        align: Any = None,
        mode: bd.Mode = bd.Mode.ADD,
    ) -> None:
        from tubecad.parts.net_arguments import net_part_design

        design = net_part_design(
            face,
            k1_lines,
            k2_lines,
            thickness,
            side,
            k1_spacing,
            k2_spacing,
            seed,
            stiffened,
            profile,
            stiffener_side,
            patches,
        )
        built = design.build_net()
        self._built = built
        solids = [bd.Solid(solid) for _, solid in built.solids]
        for solid, (name, _) in zip(solids, built.solids):
            solid.label = name
        part = bd.Compound(children=solids) if len(solids) > 1 else solids[0]
        super().__init__(part=part, rotation=rotation, align=align, mode=mode)
        self.label = type(self).__name__

    def __deepcopy__(self, memo: dict) -> Any:
        memo[id(self._built)] = self._built  # OCCT objects do not deep-copy: shared by the copies
        return super().__deepcopy__(memo)

    @property
    def design(self) -> NetDesign:
        """The design the part was built from (as a ``[host]`` spec's)."""
        return self._built.design

    @property
    def report(self) -> dict[str, Any]:
        """What was measured (``tubecad build``'s report.json): the umbilics in ``host``, the
        lines and their angles in ``net``, the wall in ``brep``, the webs in ``stiffeners``."""
        return self._built.report

    @property
    def k1(self) -> bd.ShapeList[bd.Edge]:
        """The family-1 lines as labelled edges (``k1_00``...), in every placed copy."""
        return self._lines("k1_")

    @property
    def k2(self) -> bd.ShapeList[bd.Edge]:
        """The family-2 lines as labelled edges (``k2_00``...), in every placed copy."""
        return self._lines("k2_")

    @property
    def umbilics(self) -> bd.ShapeList[bd.Vertex]:
        """The umbilics as labelled vertices (``umbilic_0``...; their types in
        ``report["host"]["umbilics"]``), in every placed copy."""
        out = []
        for place in self._places:
            for name, vertex in self._built.design.net.vertices.items():
                point = bd.Vertex(vertex).moved(place)
                point.label = name
                out.append(point)
        return bd.ShapeList(out)

    def assembly(self) -> bd.Compound:
        """The part with every name, as ``tubecad build`` writes it: its solids, then
        ``curvature_lines`` (the labelled lines) and ``umbilics``.

        Returns:
            A new build123d Compound labelled as the part.
        """
        names = [name for name, _ in self._built.solids]
        solids = []
        for i, child in enumerate(self.solids()):
            solid = bd.Solid(child.wrapped)
            solid.label = names[i % len(names)]
            solids.append(solid)
        lines = bd.Compound(label="curvature_lines", children=[*self.k1, *self.k2])
        return bd.Compound(label=self.label, children=[*solids, lines])

    @cached_property
    def _per_copy(self) -> int:
        return len(self._built.solids)

    @property
    def _places(self) -> list[bd.Location]:
        """The location of each placed copy (its wall's: the wall was built unplaced)."""
        return [solid.location for solid in list(self.solids())[:: self._per_copy]]

    def _lines(self, prefix: str) -> bd.ShapeList[bd.Edge]:
        out = []
        for place in self._places:
            for name, line in self._built.design.net.edges.items():
                if name.startswith(prefix):
                    edge = bd.Edge(line.edge).moved(place)
                    edge.label = name
                    out.append(edge)
        return bd.ShapeList(out)
