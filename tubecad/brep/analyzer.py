"""OCCT's pre-boolean check (BOPAlgo_ArgumentAnalyzer), its self-intersection part run only on
the faces that can touch (issue 24).

OCCT's self-intersection check (BOPAlgo_CheckerSI) intersects every pair of sub-shapes whose
bounding boxes overlap; on a curved tube wall three quarters of the face pairs are the inner and
outer surfaces a wall thickness apart and faces across the tube, which cannot touch. Here such a
pair is *proven* apart from the faces' own geometry before OCCT is asked: each face is held by
the convex hulls of its Bezier patches, halved as needed (tubecad.brep.face_cells), and every
sub-shape of a valid face (BRepCheck) lies within three times the largest tolerance of the face,
its edges and vertices of that surface, so each hull is taken with that radius; two faces all of
whose patch pairs are farther apart than twice their radii and the fuzzy value cannot hold an
interference OCCT would report (an interference is a contact within the shapes' tolerances).

Faces that touch (share a vertex) cannot be proven apart; a pair of them is instead proven to meet
only on what the two share, cell pair by cell pair (tubecad.brep.contact), for faces that are
whole B-spline parameter boxes (every pcurve an iso-line on a side of the box, so the box's sides
are the face's edges):

- cells farther apart than the gap, as above;
- cells sharing a whole side (the same poles, weights in proportion: the same curve) lying on
  edges of both faces: their union, as one map on a rectangle, is one-to-one with a quantitative
  bound (its Jacobian keeps a positive definite symmetric part: Gale & Nikaido), so points of the
  two closer than the gap lie within a hundredth of a cell of the common side;
- cells sharing only a corner, that corner on edges of both faces or a vertex of both: a plane
  through it has every other pole of one cell beyond the gap on one side and of the other on the
  other side.

Such a pair holds no interference OCCT would report (a contact away from the shared edges and
vertices, within the tolerances), so it is left out like a pair proven apart; this is a proof of
the geometry, not of OCCT's code: the tests compare both ways on clean walls and on shells whose
faces cross the faces they share edges with (then no proof holds and OCCT gets the pair). A
touching pair of other faces (planes, trimmed faces) goes to OCCT.

The pairs not proven (among them every touching pair without a contact proof) are covered by
groups of faces, and each group, as a compound, gets OCCT's own check (the analyzer with
SelfInterMode, so BOPAlgo_CheckerSI), one after the other, OCCT running each in parallel (forked
worker processes, one a core, were measured no faster: 10.1 s against 10.5 s on the paper wall);
groups no face of which has a box overlapping another's are run as one (the same pairs).
An interference between sub-shapes of faces F and G is computed in the whole check and in any
group holding F and G by the same code on the same data (boxes, pave blocks, tolerances of the
two sub-shapes), so the whole check finds one if and only if some group does: its first one (in
OCCT's order V/V, V/E, E/E, V/F, E/F, F/F, then each face against itself) is computed before
anything was changed, in the whole run as in the group's. The checks against a solid (vertex,
edge, face in a solid) relate a solid to sub-shapes not its own, which one solid does not have.
The other checks run on the whole part as before.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from OCP.BOPAlgo import BOPAlgo_ArgumentAnalyzer
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Compound, TopoDS_Shape

from tubecad.brep import contact
from tubecad.brep.face_cells import Cells, CellStack, FaceCells, sub_shapes, unresolved
from tubecad.occ_compat import (
    IndexedDataMapOfShapeListOfShape,
    IndexedMapOfShape,
    as_face,
    as_vertex,
    box_corners,
    shapes_in,
)
from tubecad.occ_compat import topods as topods

#: BOPAlgo_ArgumentAnalyzer's checks, all switched on (FreeCAD's "Check geometry" with
#: "BOP check" and every option): what OCCT tests before a boolean operation
ANALYZER_MODES = (
    "ArgumentTypeMode",
    "SelfInterMode",
    "SmallEdgeMode",
    "RebuildFaceMode",
    "TangentMode",
    "MergeVertexMode",
    "MergeEdgeMode",
    "ContinuityMode",
    "CurveOnSurfaceMode",
)
SELF_INTER = "SelfInterMode"
#: rounds of halving (each patch cut in two in the face's longer direction(s)) before a face
#: pair not yet proven apart is handed to OCCT
REFINEMENTS = 4
#: the face count below which the whole part is checked at once: nothing to gain (measured on
#: 10-face stiffener solids of random specs: 1.1-1.4x the whole check's time with the filter)
SMALLEST_FILTERED = 12
#: the group sizes for which the candidate graph's low modes order the faces too
SPECTRAL_FROM, SPECTRAL_UP_TO = 24, 1500
#: the cell pairs tested at once
CELL_PAIRS = 400_000
#: the cost of a face's own checks (against itself, its edges among themselves) in units of one
#: face pair's intersection, for the grouping
FACE_COST = 0.5


# --- the analyzer ---------------------------------------------------------------------------------


def _status(result) -> str:
    return str(result.GetCheckStatus()).rsplit(".", 1)[-1].removeprefix("BOPAlgo_")


def _analyzer(shape: TopoDS_Shape, modes: tuple[str, ...], parallel: bool = True):
    analyzer = BOPAlgo_ArgumentAnalyzer()
    analyzer.SetShape1(shape)
    for mode in modes:
        setattr(analyzer, mode, True)
    analyzer.SetRunParallel(parallel)
    analyzer.Perform()
    return analyzer


def _whole_findings(shape: TopoDS_Shape, modes: tuple[str, ...], parallel: bool = True) -> dict[str, int]:
    analyzer, findings = _analyzer(shape, modes, parallel), dict[str, int]()
    for result in analyzer.GetCheckResult() if analyzer.HasFaulty() else []:
        name = _status(result)
        findings[name] = findings.get(name, 0) + max(result.GetFaultyShapes1().Extent(), 1)
    return findings


def analyzer_findings(shape: object, modes: tuple[str, ...] = ANALYZER_MODES, prefilter: bool = True) -> dict[str, int]:
    """The findings of OCCT's BOPAlgo_ArgumentAnalyzer with the checks ``modes`` on (default
    all), as {status name: number of faulty sub-shapes}; {} for a shape fit for booleans.

    Each solid is checked on its own, as a CAD tool checks each part of an imported
    assembly (stiffeners overlap the wall and each other by design: that is no finding);
    a shape without solids is checked whole.

    With ``prefilter`` the self-intersection check runs on the groups of faces not proven apart
    (see the module's text: the same findings, each interfering pair once); without it, on the
    whole part, as OCCT alone does.
    """
    whole = topods(shape)
    findings: dict[str, int] = {}
    for part in sub_shapes(whole, TopAbs_SOLID) or [whole]:
        plan = plan_self_intersection(part) if prefilter and SELF_INTER in modes else None
        if plan is None or len(plan.groups) == 1:
            found = _whole_findings(part, modes)
        else:
            found = plan.run(tuple(mode for mode in modes if mode != SELF_INTER))
        for name, number in found.items():
            findings[name] = findings.get(name, 0) + number
    return findings


def _prove_apart(
    owners: list[FaceCells], pairs: list[tuple[int, int]], need: np.ndarray, refinements: int, rules: dict | None = None
) -> set:
    """The face pairs proven farther apart than need[i, j]: every pair of their cells is, after
    refining (the children of the cell pairs still open) up to ``refinements`` times; for a pair
    with a contact rule (touching faces), every pair of cells is that or proven in contact only
    along what the faces share. Taken in batches of at most CELL_PAIRS cell pairs (the memory)."""
    proven: set = set()
    batch: list[tuple[int, int]] = []
    size = 0
    for i, j in pairs:
        batch.append((i, j))
        size += len(owners[i].cells(0).points) * len(owners[j].cells(0).points)
        if size >= CELL_PAIRS:
            proven |= _prove_batch(owners, batch, need, refinements, rules or {})
            batch, size = [], 0
    return proven | _prove_batch(owners, batch, need, refinements, rules or {})


def _prove_batch(
    owners: list[FaceCells], pairs: list[tuple[int, int]], need: np.ndarray, refinements: int, rules: dict
) -> set:
    if not pairs:
        return set()
    faces = sorted({f for pair in pairs for f in pair})
    stack = CellStack(owners, faces, 0)
    sizes = {f: len(owners[f].cells(0).points) for f in faces}
    ia, ib, pid = [], [], []
    for k, (i, j) in enumerate(pairs):
        a = stack.offset[i] + np.arange(sizes[i])
        b = stack.offset[j] + np.arange(sizes[j])
        ia.append(np.repeat(a, sizes[j]))
        ib.append(np.tile(b, sizes[i]))
        pid.append(np.full(sizes[i] * sizes[j], k))
    cell_a, cell_b, owner = np.concatenate(ia), np.concatenate(ib), np.concatenate(pid)
    needs = np.array([need[i, j] for i, j in pairs])
    open_pairs: set[int] = set(range(len(pairs)))
    for level in range(refinements + 1):
        left = unresolved(stack, cell_a, cell_b, needs[owner])
        left = _not_in_contact(owners, pairs, stack, cell_a, cell_b, owner, left, level, needs, rules)
        open_pairs = set(np.unique(owner[left]).tolist())
        if not open_pairs or level == refinements:
            break
        cell_a, cell_b, owner = cell_a[left], cell_b[left], owner[left]
        faces = sorted({f for k in open_pairs for f in pairs[k]})
        finer = CellStack(owners, faces, level + 1)
        # each level-`level` cell's children in `finer`, as (sorted children, first, count)
        total = len(stack.face)
        first, count = np.zeros(total, dtype=int), np.zeros(total, dtype=int)
        order_parts, base = [], 0
        for f in faces:
            order, start, number = owners[f].kids(level)
            at = stack.offset[f] + np.arange(len(number))
            first[at], count[at] = start + base, number
            order_parts.append(order + finer.offset[f])
            base += len(order)
        order_all = np.concatenate(order_parts)
        na, nb = count[cell_a], count[cell_b]
        repeat = na * nb
        pick = np.repeat(np.arange(len(cell_a)), repeat)
        local = np.arange(repeat.sum()) - np.repeat(np.cumsum(repeat) - repeat, repeat)
        cell_a = order_all[first[cell_a[pick]] + local // nb[pick]]
        cell_b = order_all[first[cell_b[pick]] + local % nb[pick]]
        owner = owner[pick]
        stack = finer
    return {pairs[k] for k in range(len(pairs)) if k not in open_pairs}


# --- faces that touch: their cells in contact only along what the faces share ---------------------


def _box_sides(owner: FaceCells, edges: IndexedMapOfShape) -> list[set[int]] | None:
    """The edges (indices in ``edges``) on each side of the face's parameter box (u low, u high,
    v low, v high) for a face bounded by iso-parametric pcurves on the box's sides, all four
    holding some: the face is then the whole box, its sides its boundary (None for any other)."""
    box = owner.box
    if box is None or owner.pcurves is None or not owner.bounded:
        return None
    sides: list[set[int]] = [set(), set(), set(), set()]
    slack_u, slack_v = 1e-9 * max(box[1] - box[0], 1e-300), 1e-9 * max(box[3] - box[2], 1e-300)
    for edge, found in owner.pcurves:
        us, vs = np.array([p[0] for p in found]), np.array([p[1] for p in found])
        for side, (values, bound, slack) in enumerate(
            ((us, box[0], slack_u), (us, box[1], slack_u), (vs, box[2], slack_v), (vs, box[3], slack_v))
        ):
            if np.abs(values - bound).max() <= slack:
                sides[side].add(edges.FindIndex(edge))
                break
        else:
            return None
    return sides if all(sides) else None


@dataclass
class _Contact:
    """What two touching faces share: the sides of each face's box that are edges of both, the
    shared vertices' points."""

    sides: tuple[tuple[int, ...], tuple[int, ...]]
    vertices: np.ndarray  # (k, 3)
    match: float  # two poles closer than this are one point (the faces' tolerance radii)


def _contact_of(
    sides: tuple[list[set[int]] | None, list[set[int]] | None], match: float, vertices: np.ndarray
) -> _Contact | None:
    """Two touching faces' contact rule from their box sides' edges (:func:`_box_sides`)."""
    a, b = sides
    if a is None or b is None:
        return None
    shared = set().union(*a) & set().union(*b)
    allowed = tuple(tuple(k for k in range(4) if face[k] <= shared) for face in (a, b))
    return _Contact((allowed[0], allowed[1]), vertices, match)


_ROWS = ((0, slice(None)), (-1, slice(None)), (slice(None), 0), (slice(None), -1))  # sides of a grid
#: the corners of a cell (as in Cells.corners): their pole indices and the sides they lie on
_CORNERS = ((0, 0), (0, -1), (-1, 0), (-1, -1))
_CORNER_SIDES = ({0, 2}, {0, 3}, {1, 2}, {1, 3})


def _cell_sides(cells: Cells, cell: int, face: FaceCells, allowed: tuple[int, ...]) -> set[int]:
    """The cell's sides on a side of the face's box that ``allowed`` holds."""
    assert face.box is not None
    slack = 1e-12 * max(abs(x) for x in face.box) + 1e-300
    return {side for side in allowed if abs(cells.boxes[cell, side] - face.box[side]) <= slack}


def _common_side(corners: tuple[int, int]) -> int | None:
    """The side two corners of a cell span (None: a diagonal)."""
    both = _CORNER_SIDES[corners[0]] & _CORNER_SIDES[corners[1]]
    return next(iter(both)) if both else None


def _not_in_contact(
    owners: list[FaceCells],
    pairs: list[tuple[int, int]],
    stack: CellStack,
    cell_a: np.ndarray,
    cell_b: np.ndarray,
    owner: np.ndarray,
    left: np.ndarray,
    level: int,
    needs: np.ndarray,
    rules: dict[tuple[int, int], _Contact],
) -> np.ndarray:
    """The cell pairs of ``left`` not proven in contact only along what their faces share: cells
    of touching faces (a contact rule) meeting along a whole side on a shared edge of both, or at
    a corner on a shared edge of both or at a shared vertex, and otherwise farther apart than the
    pair's gap (tubecad.brep.contact)."""
    ruled = [n for n, k in enumerate(left.tolist()) if pairs[owner[k]] in rules]
    if not ruled:
        return left
    picked = left[ruled]
    tolerance = np.array([rules[pairs[owner[k]]].match for k in picked.tolist()])
    gap = np.abs(stack.corners[cell_a[picked]][:, :, None] - stack.corners[cell_b[picked]][:, None, :]).max(axis=3)
    meets = gap <= tolerance[:, None, None]  # (pairs, corners of a, corners of b)
    sides: list[tuple[int, np.ndarray, np.ndarray, float]] = []  # (row in ruled, grid a, grid b, margin)
    corners: list[tuple[int, np.ndarray, tuple[int, int], np.ndarray, tuple[int, int], float]] = []
    for row in np.nonzero(meets.any(axis=(1, 2)))[0].tolist():
        k = int(picked[row])
        i, j = pairs[owner[k]]
        rule, a, b = rules[i, j], owners[i], owners[j]
        ca, cb = int(cell_a[k] - stack.offset[i]), int(cell_b[k] - stack.offset[j])
        cells_a, cells_b = a.cells(level), b.cells(level)
        if cells_a.grids is None or cells_b.grids is None:
            continue
        ga, gb = cells_a.grids[ca], cells_b.grids[cb]
        margin = float(needs[owner[k]]) + rule.match
        on_a, on_b = _cell_sides(cells_a, ca, a, rule.sides[0]), _cell_sides(cells_b, cb, b, rule.sides[1])
        matched = [(int(x), int(y)) for x, y in zip(*np.nonzero(meets[row]))]
        if len(matched) == 2 and matched[0][0] != matched[1][0] and matched[0][1] != matched[1][1]:
            sa = _common_side((matched[0][0], matched[1][0]))
            sb = _common_side((matched[0][1], matched[1][1]))
            if sa in on_a and sb in on_b:
                row_a, row_b = ga[_ROWS[sa]], gb[_ROWS[sb]]
                flip = (matched[0][0] < matched[1][0]) != (matched[0][1] < matched[1][1])
                other = row_b[::-1] if flip else row_b
                ratio = other[:, 3] / row_a[:, 3]
                if (
                    row_a.shape == other.shape
                    and np.abs(contact.points(row_a) - contact.points(other)).max() <= rule.match
                    and np.abs(ratio - ratio[0]).max() <= 1e-12 * ratio[0]  # the same curve, not only poles
                ):
                    second = contact.oriented(gb, sb, last=False)
                    sides.append(
                        (row, contact.oriented(ga, sa, last=True), second[:, ::-1] if flip else second, margin)
                    )
                    continue
        if len(matched) != 1:
            continue
        (x, y) = matched[0]
        every_a, every_b = _cell_sides(cells_a, ca, a, (0, 1, 2, 3)), _cell_sides(cells_b, cb, b, (0, 1, 2, 3))
        at_vertex = (
            len(rule.vertices) > 0
            and np.abs(rule.vertices - stack.corners[cell_a[k], x]).max(axis=1).min() <= rule.match
            and _CORNER_SIDES[x] <= every_a  # a corner of both faces' boxes
            and _CORNER_SIDES[y] <= every_b
        )
        on_edge = bool(_CORNER_SIDES[x] & on_a) and bool(_CORNER_SIDES[y] & on_b)
        if at_vertex or on_edge:
            corners.append((row, ga, _CORNERS[x], gb, _CORNERS[y], margin))
    proven = np.zeros(len(picked), dtype=bool)
    for shape in {(job[1].shape, job[2].shape) for job in sides}:
        jobs = [job for job in sides if (job[1].shape, job[2].shape) == shape]
        ok = contact.side_contact_proven(
            np.stack([job[1] for job in jobs]), np.stack([job[2] for job in jobs]), np.array([job[3] for job in jobs])
        )
        proven[[job[0] for job in jobs]] |= ok
    for shape in {(job[1].shape, job[3].shape) for job in corners}:
        at = [job for job in corners if (job[1].shape, job[3].shape) == shape]
        ok = contact.corner_contact_proven(
            np.stack([job[1] for job in at]),
            np.array([job[2] for job in at]),
            np.stack([job[3] for job in at]),
            np.array([job[4] for job in at]),
            np.array([job[5] for job in at]),
        )
        proven[[job[0] for job in at]] |= ok
    keep = np.ones(len(left), dtype=bool)
    keep[np.array(ruled)[proven]] = False
    return left[keep]


# --- the plan: which face pairs OCCT compares, in which groups ------------------------------------


@dataclass
class SelfIntersectionPlan:
    """The self-intersection check of one part, as groups of faces for OCCT."""

    part: TopoDS_Shape
    faces: list
    pairs_overlapping: int  # face pairs whose boxes overlap: what OCCT alone would intersect
    candidates: list[tuple[int, int]]  # face pairs not proven apart
    groups: list[list[int]]
    cost: list[float] = field(default_factory=list)  # each group's estimated cost (the larger first)
    # the touching pairs proven to meet only on what they share
    in_contact: list[tuple[int, int]] = field(default_factory=list)
    _index: object = field(default=None, repr=False)

    @property
    def pairs_checked(self) -> int:
        """Distinct face pairs inside some group (those OCCT intersects, when their boxes overlap)."""
        return len({(i, j) for group in self.groups for i in group for j in group if i < j})

    def run(self, others: tuple[str, ...] = ()) -> dict[str, int]:
        """OCCT's self-intersection findings over the groups, each interfering pair once, and the
        findings of the checks ``others`` on the whole part, one after the other, OCCT in parallel."""
        cost = self.cost if len(self.cost) == len(self.groups) else [float(len(g) ** 2) for g in self.groups]
        order: list[int] = sorted(range(len(self.groups)), key=lambda k: -cost[k])
        tasks: list[int | tuple[str, ...]] = [*order]
        if others:
            tasks.insert(0, others)
        done = [(task, self.task(task, parallel=True)) for task in tasks]
        findings: dict[str, int] = {}
        seen: dict[tuple, int] = {}
        for task, found in done:
            for name, keys, number in found:
                if isinstance(task, tuple):
                    findings[name] = findings.get(name, 0) + number
                else:
                    seen.setdefault((name, *keys), number)
        for (name, *_), number in seen.items():
            findings[name] = findings.get(name, 0) + number
        return findings

    def task(self, task: int | tuple[str, ...], parallel: bool) -> list[tuple[str, tuple[int, ...], int]]:
        """One group's self-intersection findings (name, the faulty shapes' indices, their number),
        or the findings of the checks ``task`` on the whole part."""
        if isinstance(task, tuple):
            return [(name, (), number) for name, number in _whole_findings(self.part, task, parallel).items()]
        builder, compound = BRep_Builder(), TopoDS_Compound()
        builder.MakeCompound(compound)
        for i in self.groups[task]:
            builder.Add(compound, self.faces[i])
        analyzer, out = _analyzer(compound, (SELF_INTER,), parallel), []
        index = self.index()
        for result in analyzer.GetCheckResult() if analyzer.HasFaulty() else []:
            shapes = result.GetFaultyShapes1()
            keys = tuple(sorted(index.FindIndex(s) for s in shapes_in(shapes)))
            out.append((_status(result), keys, max(shapes.Extent(), 1)))
        return out

    def index(self):
        if self._index is None:
            self._index = IndexedMapOfShape()
            TopExp.MapShapes_s(self.part, self._index)
        return self._index


def plan_self_intersection(part: object, refinements: int = REFINEMENTS) -> SelfIntersectionPlan | None:
    """The groups of faces OCCT's self-intersection check must see, for a valid part made of faces
    (None for an invalid part, one with edges or vertices outside its faces, or a small one: those
    are checked whole)."""
    part = topods(part)
    faces = [as_face(f) for f in _unique(part, TopAbs_FACE)]
    if len(faces) < SMALLEST_FILTERED or not BRepCheck_Analyzer(part).IsValid() or _loose(part):
        return None
    owners = [FaceCells(face) for face in faces]
    fuzzy = BOPAlgo_ArgumentAnalyzer().FuzzyValue()
    n = len(faces)
    bounded = [o.bounded for o in owners]
    first = [o.cells(0) if o.bounded else None for o in owners]  # an unbounded face: every pair to OCCT
    low = np.array([c.low.min(axis=0) if c is not None else np.full(3, -np.inf) for c in first])
    high = np.array([c.high.max(axis=0) if c is not None else np.full(3, np.inf) for c in first])
    radius = np.array([o.radius for o in owners])
    size = float(np.nanmax(np.where(np.isfinite(high - low), high - low, np.nan))) if any(bounded) else 1.0
    # the gap two faces must keep: their radii twice over, the fuzzy value, and rounding's share
    need = 2.0 * (radius[:, None] + radius[None, :] + fuzzy) + 1e-9 * size
    gap = np.maximum(low[None, :, :] - high[:, None, :], low[:, None, :] - high[None, :, :]).max(axis=2)
    overlapping = gap <= need
    edges = IndexedMapOfShape()
    TopExp.MapShapes_s(part, TopAbs_EDGE, edges)
    sides = [_box_sides(owner, edges) for owner in owners]
    touching, shared = _touching(part, faces)
    upper = np.triu(overlapping, 1)
    rules = {}
    for i, j in zip(*np.nonzero(upper & touching)):
        rule = _contact_of((sides[i], sides[j]), radius[i] + radius[j], np.array(shared[int(i), int(j)]))
        if rule is not None:
            rules[int(i), int(j)] = rule
    in_rules = np.zeros_like(touching)
    for i, j in rules:
        in_rules[i, j] = True
    unproven = upper & ((touching & ~in_rules) | ~(np.array(bounded)[:, None] & np.array(bounded)[None, :]))
    to_prove = [(int(i), int(j)) for i, j in zip(*np.nonzero(upper & ~unproven))]
    apart = _prove_apart(owners, to_prove, need, refinements, rules)
    candidates = sorted(
        [(int(i), int(j)) for i, j in zip(*np.nonzero(unproven))] + [p for p in to_prove if p not in apart]
    )
    groups = _packed(_groups(n, candidates, overlapping, _centres(faces, low, high)), overlapping)
    pairs = int((overlapping.sum() - n) // 2)
    cost = [float(overlapping[np.ix_(g, g)].sum() - len(g)) / 2 + FACE_COST * len(g) for g in groups]
    in_contact = sorted(pair for pair in rules if pair in apart)
    return SelfIntersectionPlan(part, faces, pairs, candidates, groups, cost, in_contact=in_contact)


def _unique(shape: TopoDS_Shape, kind) -> list[TopoDS_Shape]:
    found = IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, found)
    return [found.FindKey(i) for i in range(1, found.Extent() + 1)]


def _loose(part: TopoDS_Shape) -> bool:
    """Edges outside every face or vertices outside every edge (not covered by face groups)."""
    for sub, owner in ((TopAbs_EDGE, TopAbs_FACE), (TopAbs_VERTEX, TopAbs_EDGE)):
        ancestors = IndexedDataMapOfShapeListOfShape()
        TopExp.MapShapesAndAncestors_s(part, sub, owner, ancestors)
        if any(ancestors.FindFromIndex(i).Extent() == 0 for i in range(1, ancestors.Extent() + 1)):
            return True
        if ancestors.Extent() != len(_unique(part, sub)):
            return True
    return False


def _touching(part: TopoDS_Shape, faces: list) -> tuple[np.ndarray, dict]:
    """Face pairs sharing a vertex (in contact by construction: nothing to prove by boxes), and
    each such pair's shared vertices' points."""
    index = {}
    found = IndexedMapOfShape()
    for i, face in enumerate(faces):
        found.Add(face)
        index[found.FindIndex(face)] = i
    vertex_faces = IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(part, TopAbs_VERTEX, TopAbs_FACE, vertex_faces)
    touching = np.zeros((len(faces), len(faces)), dtype=bool)
    shared: dict[tuple[int, int], list] = {}
    for v in range(1, vertex_faces.Extent() + 1):
        owners = {index[found.FindIndex(f)] for f in shapes_in(vertex_faces.FindFromIndex(v))}
        point = BRep_Tool.Pnt_s(as_vertex(vertex_faces.FindKey(v))).Coord()
        for i in owners:
            for j in owners:
                touching[i, j] = True
                shared.setdefault((i, j), []).append(point)
    return touching, shared


def _centres(faces: list, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Each face's centre for grouping: its cells' box's, or OCCT's box's for a face the
    filter could not bound (its cells' box is infinite)."""
    centres = np.zeros((len(faces), 3))
    for i, face in enumerate(faces):
        if np.all(np.isfinite(low[i])) and np.all(np.isfinite(high[i])):
            centres[i] = 0.5 * (low[i] + high[i])
        else:
            corners = box_corners(face)
            centres[i] = 0.5 * (np.array(corners[0]) + np.array(corners[1])) if corners else 0.0
    return centres


def _groups(n: int, candidates: list[tuple[int, int]], overlapping: np.ndarray, centres: np.ndarray) -> list[list[int]]:
    """Groups of faces holding every candidate pair (and every face), cheap for OCCT: a group costs
    its face pairs whose boxes overlap and its faces; a group is split in two, with the faces of
    one half that the other's candidates reach in both, while that costs less."""

    def cost(members: list[int]) -> float:
        idx = np.array(members)
        return float(overlapping[np.ix_(idx, idx)].sum() - len(idx)) / 2 + FACE_COST * len(idx)

    out: list[list[int]] = []

    def split(members: list[int], owned: set[int], required: set[tuple[int, int]]) -> None:
        # the connected pieces of the required pairs: groups of their own
        neighbours: dict[int, set[int]] = {i: set() for i in members}
        for i, j in required:
            neighbours[i].add(j)
            neighbours[j].add(i)
        seen: set[int] = set()
        pieces = []
        for start in members:
            if start in seen or (not neighbours[start] and start not in owned):
                continue
            stack, piece = [start], []
            seen.add(start)
            while stack:
                i = stack.pop()
                piece.append(i)
                for j in neighbours[i] - seen:
                    seen.add(j)
                    stack.append(j)
            pieces.append(sorted(piece))
        for piece in pieces:
            inside = set(piece)
            part_required = {(i, j) for i, j in required if i in inside}
            _bisect(piece, owned & inside, part_required, neighbours)

    def _bisect(members: list[int], owned: set[int], required: set[tuple[int, int]], neighbours) -> None:
        if len(members) <= 2:
            out.append(members)
            return
        best: tuple[float, list[int], list[int]] | None = None
        for order in _orders(members, required, centres):
            for direction in (order, order[::-1]):
                total, g1, g2 = _best_cut(direction, neighbours, overlapping)
                if best is None or total < best[0]:
                    best = (total, g1, g2)
        assert best is not None
        if best[0] >= cost(members) or len(best[1]) >= len(members):
            out.append(members)
            return
        _, g1, g2 = best
        g2_set = set(g2)
        a_set = set(g1) - g2_set  # the faces g1 owns
        split(g1, owned & a_set, {(i, j) for i, j in required if i in a_set or j in a_set})
        split(g2, owned & g2_set, {(i, j) for i, j in required if i in g2_set and j in g2_set})

    split(list(range(n)), set(range(n)), set(candidates))
    return out


def _packed(groups: list[list[int]], overlapping: np.ndarray) -> list[list[int]]:
    """The groups put together (first fit, the largest first) while no face of one has a box
    overlapping a face of another: OCCT intersects the same pairs, in fewer runs."""
    bins: list[list[int]] = []
    for group in sorted(groups, key=len, reverse=True):
        # the faces whose boxes overlap the group's (its own too)
        reach = np.asarray(np.any(overlapping[group], axis=0))
        for members in bins:
            if not reach[members].any():
                members.extend(group)
                break
        else:
            bins.append(list(group))
    return [sorted(members) for members in bins]


def _best_cut(order: list[int], neighbours: dict[int, set[int]], overlapping: np.ndarray):
    """The cheapest cut of ``order`` into a head A and a tail B: (cost, A with the faces of B its
    candidates reach, B), the cost of every cut at once. A face at position t joins the first
    group once the head holds it or a candidate partner of it: at entry[t] = min(t, partners)."""
    m = len(order)
    where = {face: t for t, face in enumerate(order)}
    entry = np.array([min([t] + [where[j] for j in neighbours[face] if j in where]) for t, face in enumerate(order)])
    idx = np.array(order)
    a, b = np.nonzero(np.triu(overlapping[np.ix_(idx, idx)], 1))
    k = np.arange(1, m)  # the head's length
    pairs_1 = np.cumsum(np.bincount(np.maximum(entry[a], entry[b]), minlength=m))[k - 1]
    faces_1 = np.cumsum(np.bincount(entry, minlength=m))[k - 1]
    pairs_2 = np.append(np.cumsum(np.bincount(a, minlength=m)[::-1])[::-1], 0)[k]  # pairs inside the tail
    total = pairs_1 + pairs_2 + FACE_COST * (faces_1 + m - k)
    best = int(np.argmin(total))
    cut = int(k[best])
    return float(total[best]), sorted(order[t] for t in range(m) if entry[t] < cut), sorted(order[cut:])


def _orders(members: list[int], required: set[tuple[int, int]], centres: np.ndarray) -> list[list[int]]:
    """Orderings of the faces to cut in halves: by the distance, in candidate pairs, from a face at
    one end of the candidate graph (a pseudo-peripheral face), and along the principal axes of
    the faces' centres."""
    neighbours: dict[int, list[int]] = {i: [] for i in members}
    for i, j in required:
        neighbours[i].append(j)
        neighbours[j].append(i)

    def levels(start: int) -> dict[int, int]:
        depth, front = {start: 0}, [start]
        while front:
            nxt = []
            for i in front:
                for j in sorted(neighbours[i]):
                    if j not in depth:
                        depth[j] = depth[i] + 1
                        nxt.append(j)
            front = nxt
        return depth

    start = members[0]
    for _ in range(2):  # the farthest face from the farthest face: an end of the graph
        depth = levels(start)
        start = max(depth, key=lambda i: (depth[i], -i))
    depth = levels(start)
    far = max(depth.values()) + 1
    orders = [sorted(members, key=lambda i: (depth.get(i, far), i))]
    if SPECTRAL_FROM <= len(members) <= SPECTRAL_UP_TO:  # the candidate graph's low modes: along it, and round it
        position = {face: k for k, face in enumerate(members)}
        laplacian = np.zeros((len(members), len(members)))
        for i, j in required:
            laplacian[position[i], position[j]] = laplacian[position[j], position[i]] = -1.0
        laplacian[np.diag_indices(len(members))] = -laplacian.sum(axis=1)
        from scipy.linalg import eigh

        vectors = eigh(laplacian, subset_by_index=[1, 3])[1]
        for mode in range(vectors.shape[1]):
            orders.append([members[k] for k in np.argsort(vectors[:, mode], kind="stable")])
    points = centres[members]
    points = points - points.mean(axis=0)
    if np.isfinite(points).all():
        _, _, axes = np.linalg.svd(points, full_matrices=False)
        for axis in axes:
            orders.append([members[k] for k in np.argsort(points @ axis, kind="stable")])
    return orders
