"""The maths belongs to the repository (issue 9): every citation of a docs/MATH.md section
points at a section that exists there, and nothing points outside the repository."""

import os
import re
from pathlib import Path

import pytest
from conftest import ROOT

MATH = ROOT / "docs" / "MATH.md"

#: where sections are cited: the package, benchmarks, samples, tests and the README
CITING = [ROOT / "tubecad", ROOT / "benchmarks", ROOT / "samples", ROOT / "tests", ROOT / "README.md", ROOT / "docs"]
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
        beside = p.parent == ROOT / "docs"  # the site's own pages link to it by its name there
        for m in re.finditer(r"[^\s(\[]*MATH\.md", text):
            cited = m.group(0).lstrip("`(\"'[")
            if not (cited.startswith("docs/MATH.md") or (beside and cited == "MATH.md")):
                line = text.count("\n", 0, m.start()) + 1
                bad.append(f"{p.relative_to(ROOT)}:{line}: {m.group(0)}")
    assert not bad, "MATH.md must be cited as docs/MATH.md:\n" + "\n".join(bad)


@pytest.mark.parametrize("needle", FORBIDDEN)
def test_nothing_points_outside_the_repository(needle):
    bad = [str(p.relative_to(ROOT)) for p in _files([ROOT]) if needle.encode() in p.read_bytes()]
    assert not bad, f"{needle!r} is not part of the repository, but these files mention it: {bad}"


# ---------------------------------------------------------------------------------------------
# the documentation site (mkdocs.yml)


def test_the_site_lists_every_page_and_builds_without_a_warning(tmp_path):
    """Every docs/*.md page is in the site's navigation, and `mkdocs build --strict` (broken
    links and anchors, API pages whose objects do not exist: all warnings, all fatal) passes."""
    import subprocess
    import sys

    import yaml

    config = yaml.safe_load((ROOT / "mkdocs.yml").read_text())
    listed = {next(iter(entry.values())) for entry in config["nav"]}
    pages = {p.name for p in (ROOT / "docs").glob("*.md")}
    assert listed == pages, f"not in mkdocs.yml's nav: {sorted(pages - listed)}; no such page: {sorted(listed - pages)}"
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(tmp_path / "site")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    assert done.returncode == 0, done.stderr
    assert "WARNING" not in done.stderr, done.stderr
    api = (tmp_path / "site" / "api" / "index.html").read_text()
    assert "CurvatureWall" in api and "RouteAxis" in api and "NetLayout" in api
    for picture in (ROOT / "docs" / "gallery").glob("*.png"):
        assert (tmp_path / "site" / "gallery" / picture.name).is_file()


def test_the_gallery_shows_every_sample():
    """Each samples/*.toml has its section, its command and its picture (a PNG) in docs/gallery.md."""
    text = (ROOT / "docs" / "gallery.md").read_text()
    for spec in sorted((ROOT / "samples").glob("*.toml")):
        picture = ROOT / "docs" / "gallery" / f"{spec.stem}.png"
        assert f"## {spec.stem}\n" in text and f"tubecad build samples/{spec.name} -o {spec.stem}.png" in text
        assert f"](gallery/{spec.stem}.png)" in text and picture.read_bytes().startswith(b"\x89PNG"), spec.name
