"""The maths belongs to the repository (issue 9): every citation of a docs/MATH.md section
points at a section that exists there, and nothing points outside the repository."""

import re
from pathlib import Path

import pytest
from conftest import ROOT

MATH = ROOT / "docs" / "MATH.md"

#: where sections are cited: the package, benchmarks, samples, tests and the README
CITING = [ROOT / "tubecad", ROOT / "benchmarks", ROOT / "samples", ROOT / "tests", ROOT / "README.md"]
TEXT_SUFFIXES = {".py", ".md", ".toml", ".txt", ".rst", ".cfg", ".ini", ".json", ".csv"}

#: never scanned: version control, the virtual environment, and generated files that
#: .gitignore keeps out of the repository (egg-info copies the README at install time)
SKIP_DIRS = {
    ".git",
    ".venv",
    "__pycache__",
    ".pytest_cache",
    ".hypothesis",
    ".benchmarks",
    "build",
    "out",
    "tubecad-paper",
}

# "MATH.md section 3", "MATH.md sections 2-5", "MATH.md, sections 3 and 4"
CITATION = re.compile(r"MATH\.md`?,?\s+sections?\s+(\d+(?:\s*(?:-|–|,|and|to)\s*\d+)*)")
HEADING = re.compile(r"^## (\d+)\.", re.MULTILINE)
# built from parts so that this file does not match itself
FORBIDDEN = ("../" + "shared", "shared/" + "MATH.md")


def _skipped(path: Path) -> bool:
    rel = path.relative_to(ROOT).parts
    return any(part in SKIP_DIRS or part.endswith(".egg-info") for part in rel)


def _files(roots: list[Path]) -> list[Path]:
    out = []
    for root in roots:
        candidates = [root] if root.is_file() else sorted(p for p in root.rglob("*") if p.is_file())
        out += [p for p in candidates if not _skipped(p)]
    return out


def _citing_texts() -> list[tuple[Path, str]]:
    this = Path(__file__).resolve()
    return [
        (p, p.read_text(encoding="utf-8", errors="replace"))
        for p in _files(CITING)
        if p.suffix in TEXT_SUFFIXES and p.resolve() != this
    ]


def _numbers(spec: str) -> list[int]:
    """'3' -> [3]; '2-5' -> [2, 3, 4, 5]; '3 and 4', '3, 4' -> [3, 4]."""
    out: list[int] = []
    for part in re.split(r"\s*(?:,|and)\s*", spec):
        ends = [int(n) for n in re.split(r"\s*(?:-|–|to)\s*", part) if n]
        out += list(range(ends[0], ends[-1] + 1))
    return out


def _sections() -> list[int]:
    return [int(n) for n in HEADING.findall(MATH.read_text(encoding="utf-8"))]


def test_math_has_its_sections_in_order():
    assert MATH.is_file(), "docs/MATH.md is missing"
    sections = _sections()
    assert len(sections) >= 10 and sections == list(range(1, len(sections) + 1)), (
        "docs/MATH.md must keep sections '## 1.' to '## 10.' (and any later ones) in order"
    )


def test_citations_exist():
    citations = [(p, m) for p, text in _citing_texts() for m in CITATION.finditer(text)]
    assert len(citations) >= 20, f"expected the package to cite docs/MATH.md, found {len(citations)} citations"
    sections = set(_sections())
    bad = [
        f"{p.relative_to(ROOT)}: '{m.group(0)}' (section {n})"
        for p, m in citations
        for n in _numbers(m.group(1))
        if n not in sections
    ]
    assert not bad, "citations of sections that docs/MATH.md does not have:\n" + "\n".join(bad)


def test_citations_name_the_file_in_the_repository():
    bad = []
    for p, text in _citing_texts():
        for m in re.finditer(r"\S*MATH\.md", text):
            if not m.group(0).lstrip("`(\"'[").startswith("docs/MATH.md"):
                line = text.count("\n", 0, m.start()) + 1
                bad.append(f"{p.relative_to(ROOT)}:{line}: {m.group(0)}")
    assert not bad, "MATH.md must be cited as docs/MATH.md:\n" + "\n".join(bad)


@pytest.mark.parametrize("needle", FORBIDDEN)
def test_nothing_points_outside_the_repository(needle):
    bad = [str(p.relative_to(ROOT)) for p in _files([ROOT]) if needle.encode() in p.read_bytes()]
    assert not bad, f"{needle!r} is not part of the repository, but these files mention it: {bad}"
