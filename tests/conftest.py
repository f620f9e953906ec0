"""Shared fixtures: one tube per axis family, each regular over its span."""

import contextlib
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from tubecad import CircleInvolute, Clothoid, CurvatureLineTube, CustomCurvature, Helix, LogSpiral

FAMILY_CASES = {
    "log_spiral": (lambda: LogSpiral(10.0, 10.0, (200.0, 1200.0)), 15.0),
    "helix": (lambda: Helix(0.0097, 10.0, (0.0, 1500.0)), 12.0),
    "circle": (lambda: Helix(0.02, 0.0, (0.0, 250.0)), 10.0),
    "clothoid": (lambda: Clothoid(400.0, 5.0, (-600.0, 900.0)), 10.0),
    "involute": (lambda: CircleInvolute(20.0, 15.0, (50.0, 2000.0)), 8.0),
    "custom": (lambda: CustomCurvature("0.004 + 0.003 * sin(2 * pi * s / 500)", 8.0, (0.0, 1500.0)), 20.0),
    "negative_beta": (lambda: LogSpiral(4.0, -35.0, (60.0, 400.0)), 5.0),
}


#: the paper's tube as a minimal spec ([axis] and [tube] only)
PAPER_SPEC = """
[axis]
curve = "log_spiral"
a = 10.0
beta_deg = 10.0
s = [200.0, 1200.0]

[tube]
radius = 15.0
"""


@pytest.fixture(params=sorted(FAMILY_CASES))
def family_tube(request) -> CurvatureLineTube:
    make_axis, radius = FAMILY_CASES[request.param]
    return CurvatureLineTube(make_axis(), radius)


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261122)


def assert_build_refused(tmp_path, spec_text: str, says: str) -> None:
    """`tubecad build` of ``spec_text`` exits 2 with one line containing ``says``, and
    writes no file."""
    from click.testing import CliRunner

    from tubecad.cli.app import cli

    spec = tmp_path / "bad.toml"
    spec.write_text(spec_text)
    out = tmp_path / "out.step"
    result = CliRunner().invoke(cli, ["build", str(spec), "-o", str(out)])
    assert result.exit_code == 2, result.output
    message = result.output.strip()
    assert "\n" not in message and says in message, message
    assert not out.exists()


#: a small stiffened wall for PAPER_SPEC: 4 x 4 layout, rings 1 and 2 and stringers 0 and 2
#: stiffened; the profile's keys follow
SMALL_STIFFENED_WALL = """
[layout]
rings = 4
stringers = 4

[wall]
thickness = 2.0

[stiffeners]
rings = [1, 2]
stringers = [0, 2]
"""


#: this folder (tests/), the repository, and its samples: tests sit in tests/unit/<package>/,
#: tests/e2e/ and tests/design/, so they take their paths from here
TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent
SAMPLES = ROOT / "samples"


def sample_wall_spec(name: str) -> str:
    """samples/NAME.toml without its [stiffeners] section (which the samples keep last): its
    wall alone, for tests that do not need the stiffeners."""
    return (SAMPLES / f"{name}.toml").read_text().split("\n[stiffeners]")[0]


def fit_circle(xy: np.ndarray) -> tuple[float, float, np.ndarray]:
    """(largest distance from the least-squares circle, its radius, its centre) of plane points."""
    import math

    sol = np.linalg.lstsq(np.c_[2 * xy, np.ones(len(xy))], (xy**2).sum(axis=1), rcond=None)[0]
    radius = math.sqrt(sol[2] + sol[0] ** 2 + sol[1] ** 2)
    return np.abs(np.linalg.norm(xy - sol[:2], axis=1) - radius).max(), radius, sol[:2]


#: a small helix tube for batches (about half a second a job): radius 5, 300 long, 3 rings, 2 stringers
SMALL_BATCH_TUBE = """
[axis]
curve = "helix"
k = 0.0097
beta_deg = 10.0
s = [0.0, 300.0]

[tube]
radius = 5.0

[layout]
rings = 3
stringers = 2
"""


# ---------------------------------------------------------------------------------------------
# external programs: one mechanism for every test that needs one
#
# `@pytest.mark.requires("ccx")` on a test (or `pytestmark` of a module), or `requires("ccx")`
# inside one: where the program is missing the test is skipped with a one-line reason, so the
# README's quick start passes on a fresh machine. In CI (CI set, as .ci/run runs) the same
# skip is a failure: CI installs these programs, and a green CI must not hide a missing step.

#: program -> (what it is, a check giving None when it is there or else why not, what installs it)
PROGRAMS = {
    "ccx": ("CalculiX", lambda: _on_path("ccx"), "apt-get install calculix-ccx"),
    "chromium": ("headless Chromium", lambda: _on_path("chromium", "chromium-browser"), "apt-get install chromium"),
    "gmsh": ("gmsh's Python module", lambda: _gmsh_loads(), 'pip install ".[test]"'),
    "freecad": ("FreeCAD's console", lambda: _on_path("freecadcmd"), "apt-get install freecad"),
}


def _on_path(*names: str) -> str | None:
    return None if any(shutil.which(n) for n in names) else "not on PATH"


def _gmsh_loads() -> str | None:
    try:
        import gmsh  # noqa: F401
    except (ImportError, OSError) as exc:  # OSError: the module is there, its libgmsh does not load
        return " ".join(f"cannot be imported: {exc}".split())
    return None


def in_ci() -> bool:
    return os.environ.get("CI", "").strip().lower() not in ("", "0", "false", "no")


def missing_reason(program: str) -> str | None:
    """None when ``program`` is there, else the one-line reason."""
    what, check, install = PROGRAMS[program]
    why = check()
    return None if why is None else f"needs {program} ({what}): {why}; {install}"


def requires(*programs: str) -> None:
    """Skip the calling test (a failure in CI) unless every one of ``programs`` is there."""
    for program in programs:
        reason = missing_reason(program)
        if reason is not None:
            try:  # reported at the test's own line, as a skip mark is
                skip = pytest.skip.Exception(reason, _use_item_location=True)
            except TypeError:  # a pytest without that keyword
                skip = pytest.skip.Exception(reason)
            skip.program_missing = True  # what the hook below looks for
            raise skip


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        f"requires(*programs): needs external programs ({', '.join(PROGRAMS)}); skipped without, failed in CI",
    )


def pytest_runtest_setup(item):
    for mark in item.iter_markers("requires"):
        requires(*mark.args)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if (
        report.skipped
        and call.excinfo is not None
        and getattr(call.excinfo.value, "program_missing", False)
        and in_ci()
    ):
        report.outcome = "failed"
        report.longrepr = f"CI={os.environ['CI']}: {call.excinfo.value.msg} (CI must install it: .ci/run)"


def _sigpipe_ignored() -> bool:
    """Whether the kernel ignores SIGPIPE for this process (Python sets it so at start, and
    reports its own record of that, not what a C library later changed: read /proc)."""
    status = Path(f"/proc/{os.getpid()}/status")
    if not status.exists():  # not Linux: nothing to read
        return True
    ignored = int(status.read_text().split("SigIgn:")[1].split()[0], 16)
    return bool(ignored >> (13 - 1) & 1)  # SIGPIPE is signal 13


@pytest.fixture(autouse=True)
def _signal_handlers_kept():
    """A test leaves this process's Ctrl-C, SIGTERM and SIGPIPE handling as it found them: a
    handler left behind (one that ends the process at once, say, or SIGPIPE back at its default,
    which gmsh.initialize() does) would end the test worker in a later test, silently, and
    pytest-xdist reports only "node down"."""
    import signal

    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    yield
    after = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    pipe_ignored = _sigpipe_ignored()
    signal.signal(signal.SIGINT, before[0])
    signal.signal(signal.SIGTERM, before[1])
    signal.signal(signal.SIGPIPE, signal.SIG_IGN)
    assert after == before, f"the test changed the SIGINT/SIGTERM handlers {before} -> {after}"
    assert pipe_ignored, "the test left SIGPIPE at its default (a write to a closed pipe ends the process): restore it"


@contextlib.contextmanager
def gmsh_initialized():
    """A gmsh session, quiet, finalized afterwards. gmsh.initialize() sets SIGPIPE back to its
    default, which ends the process at the next write to a closed pipe (a worker's, say):
    Python's SIG_IGN is restored at once."""
    import signal

    import gmsh

    gmsh.initialize(readConfigFiles=False, interruptible=False)
    signal.signal(signal.SIGPIPE, signal.SIG_IGN)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        yield gmsh
    finally:
        gmsh.finalize()


# ---------------------------------------------------------------------------------------------
# builds made once per test run, shared by every test (and every xdist worker) that needs them
#
# A build is a folder filled once, under a folder that all workers of this run share (pytest's
# base temporary folder, the parent of each worker's own), behind a file lock: the first test
# that asks builds it, the others wait and read it. Nothing is kept between runs, so no cached
# result can be stale. The folders are read-only by convention: a test writes into its tmp_path.


def _shared_root(tmp_path_factory) -> Path:
    base = tmp_path_factory.getbasetemp()
    root = (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "built-once"
    root.mkdir(exist_ok=True)
    return root


def built_once(tmp_path_factory, key: str, build) -> Path:
    """The folder ``build(folder)`` filled, made once per run under ``key`` across workers."""
    import fcntl

    root = _shared_root(tmp_path_factory)
    folder = root / key
    with open(root / f"{key}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if not (folder / ".done").exists():
            shutil.rmtree(folder, ignore_errors=True)  # an attempt that raised
            folder.mkdir()
            build(folder)
            (folder / ".done").write_text("")
    return folder


def _cli_in(folder: Path, args: list[str]) -> None:
    """Run ``tubecad ARGS`` in this process; its exit code and output go to folder/cli.json."""
    import json

    from click.testing import CliRunner

    from tubecad.cli.app import cli

    result = CliRunner().invoke(cli, args)
    (folder / "cli.json").write_text(json.dumps({"exit_code": result.exit_code, "output": result.output}))


class CliRun:
    """A shared ``tubecad`` run: the folder it wrote, its exit code and output (as click's
    Result has them, kept in root/cli.json)."""

    def __init__(self, root: Path, folder: Path | None = None):
        import json

        self.folder = root if folder is None else folder
        said = json.loads((root / "cli.json").read_text())
        self.exit_code, self.output = said["exit_code"], said["output"]

    def report(self, name: str = "r.json") -> dict:
        import json

        return json.loads((self.folder / name).read_text())


#: appended to a sample without [wall]: the wall the sample build makes of it
WALL_SECTIONS = """
[layout]
rings = 4
stringers = 3

[wall]
thickness = {thickness}
side = "centered"

[fit]
tolerance = 1e-8
"""


def sample_build_outputs(name: str) -> tuple[str, str]:
    """The files of a sample's build: a.step, and a.iges (a.brep for the closed trefoil, whose
    104 faces 320 long stay orthogonal in IGES only to |cos| 1.1e-9: the read-back check
    refuses it)."""
    return "a.step", "a.brep" if name == "trefoil_closed" else "a.iges"


@pytest.fixture(scope="session")
def sample_build(tmp_path_factory):
    """``sample_build(NAME)``: samples/NAME.toml built once per run by
    ``tubecad build spec.toml -o a.step -o a.iges --report r.json`` (a wall added to a sample
    without one: WALL_SECTIONS at a tenth of its radius), a CliRun. Every test that builds a
    sample as it is asks here, so each sample is built once in the suite."""

    def build(name: str) -> CliRun:
        def make(folder: Path) -> None:
            import tomllib

            text = (SAMPLES / f"{name}.toml").read_text()
            if "[wall]" not in text and "[host]" not in text:  # a face's net is built as it is
                text += WALL_SECTIONS.format(thickness=0.1 * tomllib.loads(text)["tube"]["radius"])
            (folder / "spec.toml").write_text(text)
            for data in SAMPLES.glob("*.step"):  # files a spec names (an edge's centreline) are relative to it
                shutil.copy(data, folder)
            outputs = [a for out in sample_build_outputs(name) for a in ("-o", str(folder / out))]
            _cli_in(folder, ["build", str(folder / "spec.toml"), *outputs, "--report", str(folder / "r.json")])

        return CliRun(built_once(tmp_path_factory, f"sample-{name}", make))

    return build


@pytest.fixture(scope="session")
def paper_run(tmp_path_factory) -> CliRun:
    """``tubecad paper -o ROOT/new/out --nu 64 --ns 501`` (a folder it creates) once per run, a
    CliRun whose folder is new/out: the suite's one run of the paper command, which every test
    of its files shares. The grid (--nu, --ns) is only that of the tube's checks in report.json."""

    def make(root: Path) -> None:
        _cli_in(root, ["paper", "-o", str(root / "new" / "out"), "--nu", "64", "--ns", "501"])

    root = built_once(tmp_path_factory, "paper", make)
    return CliRun(root, root / "new" / "out")


@pytest.fixture(scope="session")
def sample_shop(tmp_path_factory):
    """``sample_shop(NAME)``: ``tubecad shop samples/NAME.toml -o ROOT/out`` once per run, a
    CliRun whose folder is ROOT/out (a folder the command creates): the suite's one shop
    package of each sample, which every test of it shares."""

    def shop(name: str) -> CliRun:
        def make(root: Path) -> None:
            _cli_in(root, ["shop", str(SAMPLES / f"{name}.toml"), "-o", str(root / "out")])

        root = built_once(tmp_path_factory, f"shop-{name}", make)
        return CliRun(root, root / "out")

    return shop


def edges_of(shape) -> list:
    """The edges of ``shape`` (a build123d or OCP shape), as TopoDS_Edges, in explorer order."""
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    from tubecad.brep import properties as props
    from tubecad.occ_compat import as_edge

    explorer, out = TopExp_Explorer(props.topods(shape), TopAbs_EDGE), []
    while explorer.More():
        out.append(as_edge(explorer.Current()))
        explorer.Next()
    return out
