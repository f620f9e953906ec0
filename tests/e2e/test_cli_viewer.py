"""The viewer (issue 4) from the command line: `tubecad view SPEC` sends the named, coloured
tree to OCP CAD Viewer.

- No viewer: exit code 2, one line naming the port, before anything heavy is imported.
- End to end (slow): the standalone viewer on 127.0.0.1 on a free port, opened in headless
  Chromium over the DevTools protocol; `tubecad view paper` is run against it and the
  screenshot must show the model (the splash logo gone, the wall, rings and lines on screen).
"""

from __future__ import annotations

import base64
import contextlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

KEEP_SCREENSHOT = Path("/tmp/viewer_screenshot.png")  # a copy to look at (the test's own is in tmp_path)


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def tubecad_command() -> list[str]:
    exe = Path(sys.executable).parent / "tubecad"
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "tubecad.cli.console"]


def clean_env(home: Path, **extra: str) -> dict[str, str]:
    """The environment without ocp_vscode's switches, with its own HOME (the viewers' registry
    ~/.ocpvscode stays untouched)."""
    env = {k: v for k, v in os.environ.items() if k not in ("OCP_PORT", "OCP_VSCODE_PYTEST", "OCP_VIEWER_PYTEST")}
    return {**env, "HOME": str(home), "MPLBACKEND": "Agg", "PYTHONUNBUFFERED": "1", **extra}


# ---------------------------------------------------------------------------------------------
# no viewer


def test_no_viewer_is_one_line_and_exit_2_before_anything_is_built(tmp_path):
    """The port is checked first: nothing heavy (OCCT, build123d, ocp_vscode) is imported."""
    port = free_port()
    code = (
        "import sys\nfrom tubecad.cli.app import main\ntry:\n    main()\nexcept SystemExit as exc:\n"
        "    print('EXIT', exc.code, sorted(m for m in ('OCP', 'build123d', 'ocp_vscode', 'numpy') if m in sys.modules))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code, "view", "paper", "--port", str(port)],
        capture_output=True,
        text=True,
        timeout=60,
        env=clean_env(tmp_path),
    )
    assert done.stdout.strip().splitlines()[-1] == "EXIT 2 []", done.stdout + done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and f"no viewer on 127.0.0.1:{port}" in lines[0], done.stderr
    assert f"python -m ocp_viewer --port {port}" in lines[0] and "OCP CAD Viewer" in lines[0]


def test_no_viewer_console_script_and_ocp_port(tmp_path):
    """The installed console script, the port taken from OCP_PORT; a generous guard only
    (the check itself is a socket connect with a 0.5 s timeout; measured ~0.1 s in all)."""
    port = free_port()
    done = subprocess.run(
        [*tubecad_command(), "view", str(ROOT / "samples" / "helix_stiffened.toml")],
        capture_output=True,
        text=True,
        timeout=30,
        env=clean_env(tmp_path, OCP_PORT=str(port)),
    )
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and f"127.0.0.1:{port}" in done.stderr, done.stderr


# ---------------------------------------------------------------------------------------------
# end to end: the standalone viewer in headless Chromium

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
#: headless as root with a closed network; WebGL runs on SwiftShader
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--enable-unsafe-swiftshader",
    "--window-size=1200,800",
    "--remote-debugging-port=0",
]


def wait_for(condition, what, timeout: float = 60.0, process: subprocess.Popen | None = None):
    """Poll ``condition`` until it returns something true; ``what`` (a string, or a callable
    giving one) names it in the failure."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        said = what() if callable(what) else what
        if process is not None and process.poll() is not None:
            pytest.fail(f"{said}: the process ended with {process.returncode}")
        if time.monotonic() > deadline:
            pytest.fail(f"{said}: not within {timeout} s")
        time.sleep(0.2)


def stop(process: subprocess.Popen) -> None:
    """End a process we started, and its group (Chromium's helpers)."""
    if process.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(10)


def start_viewer(port: int, env: dict[str, str], log: Path) -> subprocess.Popen:
    """The standalone viewer, `python -m ocp_viewer` on 127.0.0.1:PORT, started in its own
    process group (stop() ends it) with its output written to ``log``."""
    with open(log, "w") as out:
        return subprocess.Popen(
            [sys.executable, "-m", "ocp_viewer", "--host", "127.0.0.1", "--port", str(port)],
            stdout=out,
            stderr=subprocess.STDOUT,
            env=env,
            start_new_session=True,
        )


class DevTools:
    """The least of the Chrome DevTools protocol: one page, calls answered in order."""

    def __init__(self, socket):
        self.socket = socket
        self.count = 0

    def call(self, method: str, **params):
        self.count += 1
        self.socket.send(json.dumps({"id": self.count, "method": method, "params": params}))
        while True:
            message = json.loads(self.socket.recv(timeout=60))
            if message.get("id") == self.count:
                assert "error" not in message, message
                return message["result"]

    def screenshot(self) -> bytes:
        return base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])

    def text(self) -> str:
        return self.call("Runtime.evaluate", expression="document.body.innerText")["result"]["value"]


@contextlib.contextmanager
def devtools(url: str):
    from websockets.sync.client import connect  # ocp_vscode's own dependency

    with connect(url, max_size=None, open_timeout=10) as socket:
        yield DevTools(socket)


def pixel_counts(png: bytes) -> dict[str, int]:
    """Pixels of the viewer's canvas (right of the tree, below the toolbar) by colour."""
    import io

    from PIL import Image

    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)[60:, 270:]
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    near = lambda colour, tol=25: np.abs(rgb - np.array(colour)).max(axis=-1) < tol
    return {
        "logo": int(near((0x5F, 0xA8, 0xF0)).sum()),  # the splash's blue "OCP"
        "wall": int(((b > r + 15) & (r > 140)).sum()),  # the translucent blue-grey wall over white
        "stringer_lines": int(((b > r + 60) & (b > 120) & (r < 90)).sum()),  # dark blue
        "rings": int(((r > g + 40) & (r > b + 40) & (r < 230)).sum()),  # ring frames and lines (not the red grid axis)
    }


@pytest.mark.slow
@pytest.mark.requires("chromium")  # CI installs Debian's chromium in .ci/run
def test_view_paper_in_the_standalone_viewer(tmp_path):
    """`tubecad view paper` against `python -m ocp_viewer` on a free port, seen in headless Chromium."""
    pytest.importorskip("websockets")
    port = free_port()
    env = clean_env(tmp_path)
    viewer_log = tmp_path / "viewer.log"
    processes: list[subprocess.Popen] = []
    try:
        viewer = start_viewer(port, env, viewer_log)
        processes.append(viewer)
        url = f"http://127.0.0.1:{port}/viewer"
        wait_for(lambda: "OCP Viewer runs at" in viewer_log.read_text(), "the viewer starts", process=viewer)

        profile = tmp_path / "chromium-profile"
        browser = subprocess.Popen(
            [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", url],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
        processes.append(browser)
        active = profile / "DevToolsActivePort"
        wait_for(lambda: active.is_file() and active.read_text().strip(), "Chromium's DevTools port", process=browser)
        devtools_port = int(active.read_text().split()[0])

        def page_socket():
            with urllib.request.urlopen(f"http://127.0.0.1:{devtools_port}/json/list", timeout=5) as answer:
                pages = [t for t in json.load(answer) if t["type"] == "page" and t["url"].startswith(url)]
            return pages[0]["webSocketDebuggerUrl"] if pages else None

        with devtools(wait_for(page_socket, "the viewer page in Chromium", process=browser)) as page:
            # the page registers with the viewer, which relays models only to a registered page
            wait_for(lambda: "Browser as viewer client registered" in viewer_log.read_text(), "the page registers")

            def splash_on_screen():
                png = page.screenshot()
                return png if pixel_counts(png)["logo"] > 5000 else None

            empty = wait_for(splash_on_screen, "the splash logo on the empty viewer")
            (tmp_path / "empty.png").write_bytes(empty)
            before = pixel_counts(empty)

            done = subprocess.run(
                [*tubecad_command(), "view", "paper", "--port", str(port)],
                capture_output=True,
                text=True,
                timeout=600,
                env=env,
            )
            assert done.returncode == 0, done.stderr
            assert done.stdout.strip() == (
                f"paper: wall, 9 ring and 2 stringer stiffeners, 38 curvature lines "
                f"sent to the viewer on 127.0.0.1:{port}"
            )

            seen: dict[str, int] = {}

            def model_on_screen():
                png = page.screenshot()
                counts = pixel_counts(png)
                seen.update(counts)
                shown = (
                    counts["logo"] < 50
                    and counts["wall"] > 3000
                    and counts["stringer_lines"] > 3000
                    and counts["rings"] > 500
                )
                return (png, counts) if shown else None

            # thresholds: measured empty (splash) ~22000 logo, 0 wall, ~1200 blue, ~10 ring pixels;
            # the paper ~0 logo, ~17500 wall, ~14900 blue, ~1900 ring pixels (1200 x 657 page)
            png, after = wait_for(
                model_on_screen, lambda: f"the paper on screen (empty: {before}, last: {seen})", timeout=120
            )
            print("pixel counts, empty viewer:", before, "with the paper:", after)
            (tmp_path / "paper.png").write_bytes(png)
            with contextlib.suppress(OSError):
                KEEP_SCREENSHOT.write_bytes(png)
            assert after["stringer_lines"] > 3 * before["stringer_lines"] and after["wall"] > before["wall"] + 3000
            tree = page.text()  # the viewer's navigation tree names the parts
            for name in ("paper", "wall", "ring_01", "ring_09", "stringer_00", "stringer_04", "curvature_lines"):
                assert name in tree, name
    finally:
        for process in reversed(processes):
            stop(process)


@pytest.mark.slow
def test_a_viewer_with_no_browser_page_is_told_not_sent(tmp_path):
    """`python -m ocp_viewer` running with no page open takes a model and only logs "No
    browser registered": `tubecad view` must not say "sent", but exit 2 saying how to open one."""
    pytest.importorskip("websockets")
    port = free_port()
    env = clean_env(tmp_path)
    viewer_log = tmp_path / "viewer.log"
    spec = tmp_path / "small.toml"
    spec.write_text('[axis]\ncurve = "helix"\nk = 0.01\nbeta_deg = 10.0\ns = [0.0, 200.0]\n\n[tube]\nradius = 5.0\n')
    viewer = start_viewer(port, env, viewer_log)
    try:
        wait_for(lambda: "OCP Viewer runs at" in viewer_log.read_text(), "the viewer starts", process=viewer)
        done = subprocess.run(
            [*tubecad_command(), "view", str(spec), "--port", str(port)],
            capture_output=True,
            text=True,
            timeout=300,
            env=env,
        )
        assert done.returncode == 2 and "sent" not in done.stdout, (done.stdout, done.stderr)
        assert done.stderr.strip().splitlines()[-1] == (
            f"Error: the viewer on 127.0.0.1:{port} took the model, but no browser page shows it: open "
            f"http://127.0.0.1:{port}/viewer (or reload it), then run this again"
        )
        assert "No browser registered" in viewer_log.read_text()  # the viewer's own word for it
    finally:
        stop(viewer)
