"""The viewer (issue 4): `tubecad view SPEC` and `tubecad.show(...)` send the named, coloured
tree to OCP CAD Viewer.

- What would be sent (OCP_VSCODE_PYTEST=1, no viewer needed): part names, colours, the wall's
  alpha, and bounding boxes of the tessellation checked against the exact tube.
- `tubecad view` with no viewer, and end to end against the standalone viewer in headless
  Chromium: tests/e2e/test_cli_viewer.py.
"""

from __future__ import annotations

import os
import socket

import numpy as np
import pytest


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


# ---------------------------------------------------------------------------------------------
# what would be sent


def sent_parts(shown) -> dict[str, dict]:
    """Leaf name -> type, colour, alpha and bounding box (min, max) of its tessellation."""
    (instances, shapes, _config, _count), _mapping = shown.sent
    out: dict[str, dict] = {}

    def walk(node: dict) -> None:
        for part in node.get("parts", []):
            assert part.get("loc") in (None, ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))), part["name"]
            if "parts" in part:
                out[part["name"]] = {"type": "group"}
                walk(part)
                continue
            shape = part["shape"]
            flat = instances[shape["ref"]]["vertices"] if "ref" in shape else shape.get("edges", shape.get("vertices"))
            points = np.asarray(flat, dtype=float).reshape(-1, 3)
            out[part["name"]] = {
                "type": part["type"],
                "color": part["color"],
                "alpha": part.get("alpha", 1.0),
                "bbox": (points.min(axis=0), points.max(axis=0)),
            }

    walk(shapes)
    return out


def hex_colour(rgb) -> str:
    return "#" + "".join(f"{round(c * 255):02x}" for c in tuple(rgb)[:3])


def circle_half_extent(radius: float, normal: np.ndarray) -> np.ndarray:
    """Half the bounding box of a circle of ``radius`` about ``normal``: r sqrt(1 - n_i^2)."""
    return radius * np.sqrt(np.clip(1.0 - normal**2, 0.0, None))


def tube_bbox(axis, radius: float, span) -> tuple[np.ndarray, np.ndarray]:
    """The exact bounding box of the tube of ``radius`` (its circles' extents along the axis)."""
    s = np.linspace(*span, 20001)
    centre, tangent = axis.position(s), axis.frame(s)[0]
    half = circle_half_extent(radius, tangent)
    return (centre - half).min(axis=0), (centre + half).max(axis=0)


@pytest.fixture(scope="module")
def small_wall():
    from tubecad.brep import NetLayout, build_wall_solid
    from tubecad.spec.paper import paper_tube
    from tubecad.stiffeners.assembly import build_stiffeners
    from tubecad.stiffeners.profiles import Profile

    tube = paper_tube()
    build = build_wall_solid(tube, 2.0, "centered", NetLayout.equal(tube, 5, 4))
    stiffeners = build_stiffeners(build, [1, 3], [0, 2], Profile("flat", 2.0, 1.0), "inside")
    return build, stiffeners


@pytest.mark.slow
def test_show_records_the_named_coloured_tree(monkeypatch, small_wall):
    """Names, colours, the wall's alpha and the bounding boxes of what would be sent."""
    import tubecad
    from tubecad.integrations.viewer import LINE_RING_RGB, LINE_STRINGER_RGB, WALL_ALPHA
    from tubecad.stiffeners.assembly import RING_COLOUR, STRINGER_COLOUR, WALL_COLOUR

    monkeypatch.setenv("OCP_VSCODE_PYTEST", "1")
    monkeypatch.delenv("OCP_VIEWER_PYTEST", raising=False)
    build, stiffeners = small_wall
    shown = tubecad.show(build, stiffeners=stiffeners, port=free_port())  # nothing listens: recorded, not sent
    assert os.environ.get("OCP_VIEWER_PYTEST") is None  # set for the call only
    parts = sent_parts(shown)
    layout, axis = build.layout, build.surfaces[0].tube.axis
    r_out, r_in = build.radii
    n_rings, n_stringers = len(layout.s_rings), len(layout.stringers_deg)
    lines = [f"line_ring_{i:02d}{sfx}" for sfx in ("", "_inner") for i in range(n_rings)]
    lines += [f"line_stringer_{j:02d}{sfx}" for sfx in ("", "_inner") for j in range(n_stringers)]
    assert set(parts) == {"wall", "ring_01", "ring_03", "stringer_00", "stringer_02", "curvature_lines", *lines}
    assert shown.names[:5] == ["wall", "ring_01", "ring_03", "stringer_00", "stringer_02"]
    assert shown.recorded and shown.summary().startswith(
        f"tubecad: wall, 2 ring and 2 stringer stiffeners, {len(lines)} curvature lines recorded"
    )

    # colours: the wall translucent, rings and stringers (stiffeners and lines) each their own
    wall = parts["wall"]
    assert wall["type"] == "shapes" and wall["color"] == hex_colour(WALL_COLOUR) and wall["alpha"] == WALL_ALPHA == 0.4
    for name in ("ring_01", "ring_03"):
        assert parts[name]["color"] == hex_colour(RING_COLOUR) and parts[name]["alpha"] == 1.0
    for name in ("stringer_00", "stringer_02"):
        assert parts[name]["color"] == hex_colour(STRINGER_COLOUR) and parts[name]["alpha"] == 1.0
    for name in lines:
        assert parts[name]["type"] == "edges"
        assert parts[name]["color"] == hex_colour(LINE_RING_RGB if name.startswith("line_ring_") else LINE_STRINGER_RGB)
    palette = (WALL_COLOUR, RING_COLOUR, STRINGER_COLOUR, LINE_RING_RGB, LINE_STRINGER_RGB)
    assert len({hex_colour(c) for c in palette}) == len(palette)

    # bounding boxes against the exact tube: the mesh's vertices lie on it, so its box is the
    # tube's to within the tessellation's chord error (measured: wall 0.06, ring lines 0.002)
    low, high = tube_bbox(axis, r_out, axis.span)
    np.testing.assert_allclose(wall["bbox"][0], low, atol=0.1)
    np.testing.assert_allclose(wall["bbox"][1], high, atol=0.1)
    for i in range(n_rings):  # a ring line is the circle about c(s_i) with normal t(s_i)
        centre, tangent = axis.position(layout.s_rings[i]), axis.frame(layout.s_rings[i])[0]
        for name, radius in ((f"line_ring_{i:02d}", r_out), (f"line_ring_{i:02d}_inner", r_in)):
            lo, hi = parts[name]["bbox"]
            np.testing.assert_allclose((lo + hi) / 2, centre, atol=0.01, err_msg=name)
            np.testing.assert_allclose((hi - lo) / 2, circle_half_extent(radius, tangent), atol=0.01, err_msg=name)
    width = stiffeners[0].profile.thickness
    for i in (1, 3):  # a ring frame (flat bar inside, on the inner wall) spans the circle of radius r_in,
        s_i = layout.s_rings[i]  # its faces in the normal planes at s_i -+ width / 2: wider outside the bend
        tangent = axis.frame(s_i)[0]
        lo, hi = parts[f"ring_{i:02d}"]["bbox"]
        np.testing.assert_allclose(
            (hi - lo) / 2, circle_half_extent(r_in, tangent) + width / 2 * np.abs(tangent), atol=0.02
        )
        off_centre = width / 2 * r_in * float(axis.curvature(s_i))  # measured 0.107 at s = 450
        assert np.abs((lo + hi) / 2 - axis.position(s_i)).max() < off_centre + 0.02
    for name, part in parts.items():  # everything lies within the wall's box
        if "bbox" in part:
            assert np.all(part["bbox"][0] >= low - 0.1) and np.all(part["bbox"][1] <= high + 0.1), name


@pytest.mark.slow
def test_show_of_a_spec_with_panels(monkeypatch, tmp_path):
    """A spec path: [panels] become the wall's children, each translucent."""
    from conftest import PAPER_SPEC

    import tubecad

    spec = tmp_path / "panelled.toml"
    spec.write_text(
        PAPER_SPEC + "\n[layout]\nrings = 3\nstringers = 4\n\n[wall]\nthickness = 2.0\n\n[panels]\nseams = [0, 2]\n"
    )
    monkeypatch.setenv("OCP_VSCODE_PYTEST", "1")
    shown = tubecad.show(spec)
    parts = sent_parts(shown)
    panels = [f"panel_r{i}_s{j}" for i in range(2) for j in range(2)]
    assert parts["wall"] == {"type": "group"} and shown.trees[0].label == "panelled"
    assert shown.names[: 1 + len(panels)] == ["wall", *panels]
    assert all(parts[p]["alpha"] == 0.4 and parts[p]["type"] == "shapes" for p in panels)
    assert not any(n.startswith(("ring_", "stringer_")) for n in parts)
    assert sum(n.startswith("line_") for n in parts) == 2 * (3 + 4)
    assert shown.summary().startswith("panelled: 4 panels, 14 curvature lines")


def test_show_refuses_what_it_cannot_show(monkeypatch):
    import tubecad
    from tubecad import ParameterError, SpecError

    monkeypatch.setenv("OCP_VSCODE_PYTEST", "1")
    with pytest.raises(ParameterError, match="show needs something to show"):
        tubecad.show()
    with pytest.raises(ParameterError, match="got int"):
        tubecad.show(3)
    with pytest.raises(ParameterError, match="stiffeners, panels, lines and fuse go with a TubeBuild"):
        tubecad.show("paper", lines=False)
    with pytest.raises(ParameterError, match=r"wall_alpha must be in \(0, 1\], got 0"):
        tubecad.show("paper", wall_alpha=0)
    with pytest.raises(SpecError, match="cannot read spec file"):
        tubecad.show("no_such_spec.toml")
    with pytest.raises(ParameterError, match=r"port must be a port number in \[1, 65535\], got 0"):
        tubecad.show("paper", port=0)
    monkeypatch.setenv("OCP_PORT", "abc")
    with pytest.raises(ParameterError, match="OCP_PORT must be a port number"):
        tubecad.show("paper")


@pytest.mark.slow
def test_show_of_a_host_spec_sends_the_nets_wall_lines_webs_and_umbilics(monkeypatch, tmp_path):
    """A [host] spec: the face's net as `tubecad build` writes it, the wall translucent, the
    lines coloured by family; everything inside the dome's box (the 2:1 ellipse a = 500,
    c = 250 turned about z: |x|, |y| <= a, 0 <= z <= c)."""
    from conftest import ROOT

    import tubecad
    from tubecad.integrations.viewer import LINE_RING_RGB, LINE_STRINGER_RGB

    text = (ROOT / "samples" / "dome.toml").read_text().replace('step = "', f'step = "{ROOT / "samples"}/')
    spec = tmp_path / "dome.toml"
    spec.write_text(text)
    monkeypatch.setenv("OCP_VSCODE_PYTEST", "1")
    shown = tubecad.show(spec)
    parts = sent_parts(shown)
    assert shown.trees[0].label == "dome" and parts["wall"]["alpha"] == 0.4
    assert sorted(n for n in parts if n.startswith("stiffener_")) == [f"stiffener_k1_0{i}" for i in (1, 3, 5)]
    assert parts["k1_02"]["color"] == hex_colour(LINE_RING_RGB)
    assert parts["k2_05"]["color"] == hex_colour(LINE_STRINGER_RGB)
    assert sum(n.startswith(("k1_", "k2_")) for n in parts) == 6 + 8
    for name, part in parts.items():
        if "bbox" in part:
            low, high = part["bbox"]
            assert np.all(np.abs(low[:2]) <= 500 + 1e-6) and np.all(np.abs(high[:2]) <= 500 + 1e-6), name
            assert low[2] >= -1e-6 and high[2] <= 250 + 1e-6, name
    assert shown.summary().startswith("dome: wall, 3 stiffeners, 14 curvature lines")
