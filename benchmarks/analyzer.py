"""Where the time of OCCT's pre-boolean check goes on a tubecad wall (issue 24).

``python benchmarks/analyzer.py [--json FILE]`` builds the paper's wall (samples/paper_log_spiral.toml:
11 rings x 8 stringers, 162 faces) and times, in one process:

1. ``BOPAlgo_ArgumentAnalyzer`` with each check on alone (``tubecad.brep.properties.analyzer_findings``);
2. its self-intersection part as ``BOPAlgo_CheckerSI`` stopped at each level (3: up to vertex/face,
   4: edge/face, 5: face/face, the whole check), in parallel and serial, and with OCCT's oriented
   boxes as the pair prefilter (``SetUseOBB``, which the analyzer does not pass on);
3. the self-intersection check against the fit tolerance (1e-4 .. 1e-10: the v knots per face)
   and against the layout (the number of faces, so of face pairs whose boxes overlap);
4. the same check on the peer: the tube as one swept solid (MakePipeShell, CorrectedFrenet, the
   paper's spine) beside tubecad's capped tube with the fewest faces (2 rings x 1 stringer);
5. the face pairs whose boxes overlap, by what they share (an edge, only a vertex, nothing: the
   wall's inner and outer surfaces, faces across the tube), each class's count and its mean
   time per pair in OCCT's face/face intersection (IntTools_FaceFace, 60 pairs sampled per class);
6. every check, old (``prefilter=False``: OCCT on the whole part) against new (the face pairs proven
   apart, and the touching pairs proven to meet only on what they share, left out:
   ``tubecad.brep.analyzer``), on the paper wall and on a 98-face wall (7 rings x 8 stringers): the
   seconds, the face pairs OCCT intersects either way, the groups.

7. (``--only random --cases N``) the same comparison, self-intersection alone, on every solid of at
   most 260 faces of the first N cases of the random-spec run (benchmarks/random_specs.py, seed
   2026), two cases at a time.

``--only prefilter`` runs part 6 alone and puts it into the JSON file given, keeping the rest
(``--only random`` likewise part 7).

Every shape checked is valid with no finding; only the times differ.
"""

from __future__ import annotations

import argparse
import json
import os
import time
import tomllib
from pathlib import Path

from OCP.Bnd import Bnd_Box
from OCP.BOPAlgo import BOPAlgo_CheckerSI
from OCP.BRep import BRep_Tool
from OCP.BRepBndLib import BRepBndLib
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer

from tubecad.brep.analyzer import plan_self_intersection
from tubecad.brep.properties import ANALYZER_MODES, analyzer_findings, is_valid, topods
from tubecad.occ_compat import ListOfShape, as_face
from tubecad.spec.build import build_from_spec
from tubecad.spec.parse import parse_spec

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "samples" / "paper_log_spiral.toml"


def _list_of_shape(shape):
    shapes = ListOfShape()  # the OCP name that moved between generations: tubecad.occ_compat
    shapes.Append(shape)
    return shapes


def faces_of(shape) -> list:
    explorer, faces = TopExp_Explorer(topods(shape), TopAbs_FACE), []
    while explorer.More():
        faces.append(explorer.Current())
        explorer.Next()
    return faces


def overlapping_pairs(shape) -> int:
    """Face pairs whose bounding boxes (BRepBndLib, as BOPDS makes them) overlap."""
    boxes = []
    for face in faces_of(shape):
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box)
        boxes.append(box)
    return sum(1 for i, a in enumerate(boxes) for b in boxes[i + 1 :] if not a.IsOut(b))


def v_knots(shape) -> int:
    """Knot spans in v summed over the B-spline faces (what OCCT's samplers scale with)."""
    total = 0
    for face in faces_of(shape):
        surface = BRep_Tool.Surface_s(as_face(face))
        if surface.DynamicType().Name() == "Geom_BSplineSurface":
            total += surface.NbVKnots() - 1
    return total


def timed(call) -> tuple[float, object]:
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result


def checker_si(shape, level: int = 5, parallel: bool = True, obb: bool = False) -> float:
    checker = BOPAlgo_CheckerSI()
    checker.SetArguments(_list_of_shape(topods(shape)))
    checker.SetLevelOfCheck(level)
    checker.SetRunParallel(parallel)
    checker.SetUseOBB(obb)
    seconds, _ = timed(checker.Perform)
    assert not checker.HasErrors()
    return seconds


def wall(tolerance: float = 1e-8, rings: int = 11, stringers: int = 8):
    data = tomllib.loads(SPEC.read_text())
    data["fit"]["tolerance"] = tolerance
    data["layout"] = {"rings": rings, "stringers": stringers}
    return build_from_spec(parse_spec(data, str(SPEC))).shape


def self_inter(shape) -> float:
    seconds, findings = timed(lambda: analyzer_findings(shape, ("SelfInterMode",)))
    assert findings == {}, findings
    return seconds


def peer_sweep():
    """The paper tube as MakePipeShell (CorrectedFrenet) sweeps it along the 1001-point spine."""
    from peers import occt_pipe_shell, spine

    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    return occt_pipe_shell("CorrectedFrenet")(tube, spine(tube))[0].wrapped


def capped_tube():
    from tubecad.brep import NetLayout, build_tube_solid
    from tubecad.spec.paper import paper_tube

    tube = paper_tube()
    return build_tube_solid(tube, NetLayout.equal(tube, 2, 1)).shape


def pair_classes(shape, sample: int = 60) -> dict:
    """The overlapping face pairs by what they share, with IntTools_FaceFace's mean time per pair."""
    import random

    from OCP.IntTools import IntTools_FaceFace
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_VERTEX

    faces = [as_face(f) for f in faces_of(shape)]

    def subs(face, kind) -> list:
        explorer, out = TopExp_Explorer(face, kind), []
        while explorer.More():
            out.append(explorer.Current())
            explorer.Next()
        return out

    edges, vertices = [subs(f, TopAbs_EDGE) for f in faces], [subs(f, TopAbs_VERTEX) for f in faces]
    boxes = []
    for face in faces:
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box)
        boxes.append(box)
    classes: dict[str, list] = {"an edge": [], "only a vertex": [], "nothing": []}
    for i in range(len(faces)):
        for j in range(i + 1, len(faces)):
            if boxes[i].IsOut(boxes[j]):
                continue
            if any(a.IsSame(b) for a in edges[i] for b in edges[j]):
                classes["an edge"].append((i, j))
            elif any(a.IsSame(b) for a in vertices[i] for b in vertices[j]):
                classes["only a vertex"].append((i, j))
            else:
                classes["nothing"].append((i, j))
    random.seed(2)
    out = {}
    for name, pairs in classes.items():
        chosen = random.sample(pairs, min(sample, len(pairs)))
        seconds = []
        for i, j in chosen:
            start = time.perf_counter()
            intersector = IntTools_FaceFace()
            intersector.SetParameters(True, True, True, 1e-7)
            intersector.Perform(faces[i], faces[j])
            seconds.append(time.perf_counter() - start)
        mean = sum(seconds) / max(len(seconds), 1)
        out[name] = {"pairs": len(pairs), "ms_per_pair": round(1e3 * mean, 1), "serial_s": round(mean * len(pairs), 1)}
    return out


def timed_cpu(call) -> tuple[float, float, object]:
    """(wall seconds, CPU seconds of this process, its threads and its finished children, result):
    the CPU seconds tell the work when other jobs share the cores."""
    import resource

    def cpu() -> float:
        children = resource.getrusage(resource.RUSAGE_CHILDREN)
        return time.process_time() + children.ru_utime + children.ru_stime

    start, cpu_start = time.perf_counter(), cpu()
    result = call()
    return time.perf_counter() - start, cpu() - cpu_start, result


def prefilter(layouts=((11, 8), (7, 8))) -> list[dict]:
    """Every check, old (OCCT on the whole part) and new (the pairs proven apart left out)."""
    rows = []
    for rings, stringers in layouts:
        shape = topods(wall(1e-8, rings, stringers))
        faces = faces_of(shape)
        plan_s, plan = timed(lambda: plan_self_intersection(shape))
        old_s, old_cpu, old = timed_cpu(lambda: analyzer_findings(shape, prefilter=False))
        new_s, new_cpu, new = timed_cpu(lambda: analyzer_findings(shape))
        assert old == new == {}, (old, new)
        boxes = []
        for face in plan.faces:
            box = Bnd_Box()
            BRepBndLib.Add_s(face, box)
            boxes.append(box)
        together = {(i, j) for group in plan.groups for i in group for j in group if i < j}
        rows.append(
            {
                "rings": rings,
                "stringers": stringers,
                "faces": len(faces),
                "old_all_modes_s": round(old_s, 2),
                "new_all_modes_s": round(new_s, 2),
                "old_all_modes_cpu_s": round(old_cpu, 2),
                "new_all_modes_cpu_s": round(new_cpu, 2),
                "load_average": round(os.getloadavg()[0], 2),
                "plan_s": round(plan_s, 2),
                "face_pairs_overlapping": plan.pairs_overlapping,
                "face_pairs_touching_proven": len(plan.in_contact),
                "face_pairs_not_proven_apart": len(plan.candidates),
                "face_pairs_handed_to_occt": sum(1 for i, j in together if not boxes[i].IsOut(boxes[j])),
                "groups": len(plan.groups),
                "largest_group": max(len(group) for group in plan.groups),
            }
        )
    return rows


def random_case(index: int) -> dict:
    """Self-intersection findings both ways on each solid of random-spec case ``index``."""
    import tempfile

    import random_specs
    from OCP.TopAbs import TopAbs_SOLID

    from tubecad.brep.analyzer import sub_shapes
    from tubecad.core.errors import TubecadError
    from tubecad.spec import build_spec

    with tempfile.TemporaryDirectory() as folder:
        case = random_specs.make_case(2026, index, Path(folder))
        row: dict = {"index": index, "kind": case.kind, "canal": case.canal, "stiffeners": case.stiffeners}
        try:
            built = build_spec(parse_spec(case.spec, source="random.toml", base=Path(folder)))
        except TubecadError:
            return {**row, "outcome": "refused"}
    row.update(outcome="built", solids=[])
    shape = topods(built.shape)
    for solid in sub_shapes(shape, TopAbs_SOLID) or [shape]:
        item: dict = {"faces": len(faces_of(solid))}
        new_s, new = timed(lambda solid=solid: analyzer_findings(solid, ("SelfInterMode",)))
        item.update(new=new, new_s=round(new_s, 2))
        if item["faces"] <= 260:
            old_s, old = timed(lambda solid=solid: analyzer_findings(solid, ("SelfInterMode",), prefilter=False))
            item.update(old=old, old_s=round(old_s, 2), same=old == new)
        row["solids"].append(item)
    return row


def random_cases(cases: int) -> dict:
    from multiprocessing import Pool

    with Pool(2) as pool:
        rows = list(pool.imap(random_case, range(cases)))
    compared = [s for r in rows for s in r.get("solids", []) if "same" in s]
    return {
        "cases": cases,
        "built": sum(r["outcome"] == "built" for r in rows),
        "solids_compared": len(compared),
        "all_the_same": all(s["same"] for s in compared),
        "rows": rows,
    }


def run() -> dict:
    paper = wall()
    assert is_valid(paper)
    result: dict = {"faces": len(faces_of(paper)), "face_pairs_overlapping": overlapping_pairs(paper)}
    result["modes_s"] = {}
    for mode in ANALYZER_MODES:
        seconds, findings = timed(lambda mode=mode: analyzer_findings(paper, (mode,)))
        assert findings == {}, (mode, findings)
        result["modes_s"][mode] = round(seconds, 2)
    result["all_modes_s"] = round(timed(lambda: analyzer_findings(paper))[0], 2)
    result["pairs_by_what_they_share"] = pair_classes(paper)
    result["checker_levels_s"] = {level: round(checker_si(paper, level), 2) for level in (3, 4, 5)}
    result["checker_serial_s"] = round(checker_si(paper, parallel=False), 2)
    result["checker_obb_s"] = round(checker_si(paper, obb=True), 2)
    result["by_tolerance"] = []
    for tolerance in (1e-4, 1e-6, 1e-8, 1e-10):
        shape = wall(tolerance)
        result["by_tolerance"].append(
            {"tolerance": tolerance, "v_knot_spans": v_knots(shape), "self_inter_s": round(self_inter(shape), 2)}
        )
    result["by_layout"] = []
    for rings, stringers in ((2, 1), (3, 2), (6, 4), (11, 8)):
        shape = wall(1e-8, rings, stringers)
        result["by_layout"].append(
            {
                "rings": rings,
                "stringers": stringers,
                "faces": len(faces_of(shape)),
                "pairs": overlapping_pairs(shape),
                "self_inter_s": round(self_inter(shape), 2),
            }
        )
    peer, tube = peer_sweep(), capped_tube()
    result["prefilter"] = prefilter()
    result["peer"] = {
        "makepipeshell_faces": len(faces_of(peer)),
        "makepipeshell_v_knot_spans": v_knots(peer),
        "makepipeshell_self_inter_s": round(self_inter(peer), 2),
        "tubecad_tube_faces": len(faces_of(tube)),
        "tubecad_tube_v_knot_spans": v_knots(tube),
        "tubecad_tube_self_inter_s": round(self_inter(tube), 2),
    }
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, help="write the results there")
    parser.add_argument(
        "--only", choices=["prefilter", "random"], help="run this part alone (kept with the rest of --json)"
    )
    parser.add_argument("--cases", type=int, default=25, help="random-spec cases for --only random")
    args = parser.parse_args()
    if args.only:
        result = json.loads(args.json.read_text()) if args.json and args.json.exists() else {}
        if args.only == "prefilter":
            result["prefilter"] = prefilter()
        else:
            result["random_specs"] = random_cases(args.cases)
    else:
        result = run()
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        args.json.write_text(text + "\n")


if __name__ == "__main__":
    main()
