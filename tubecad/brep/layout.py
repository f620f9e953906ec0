"""Which curvature lines become B-rep edges: ring frames s_i and stringers at angles theta_j."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from tubecad.core.errors import ParameterError
from tubecad.surface import CurvatureLineSurface

DEFAULT_RINGS = 11
DEFAULT_STRINGERS = 8
#: upper bounds that keep a B-rep buildable (and a typo like rings = 100000000 from exhausting memory)
MAX_RINGS = 10_000
MAX_STRINGERS = 1_000
MAX_FACES = 100_000


@dataclass(frozen=True)
class NetLayout:
    """Ring frames at arc lengths ``s_rings`` (both span ends included, increasing) and
    stringers at angles ``stringers_deg`` around the tube (from the RMF normal r1).

    Made with :meth:`equal` or :meth:`explicit`, which check the values against a surface;
    the constructor takes them as they are.

    Args:
        s_rings: the rings' arc lengths s, model units, increasing, both span ends included.
        stringers_deg: the stringers' angles in degrees, in [0, 360), increasing, measured
            around the tube from the rotation-minimising normal r1.
    """

    s_rings: tuple[float, ...]
    stringers_deg: tuple[float, ...]

    @classmethod
    def equal(
        cls, tube: CurvatureLineSurface, rings: int = DEFAULT_RINGS, stringers: int = DEFAULT_STRINGERS
    ) -> NetLayout:
        """``rings`` frames equally spaced in s (:func:`equal_rings`: ends included on an open
        axis, N distinct rings on a closed one), ``stringers`` at 360 j / M deg (a route's
        joints are added, see :meth:`explicit`)."""
        return cls.explicit(tube, equal_rings(tube, rings, stringers), equal_stringers(stringers))

    @classmethod
    def explicit(
        cls,
        tube: CurvatureLineSurface,
        s_rings: Sequence[float] | np.ndarray,
        stringers_deg: Sequence[float] | np.ndarray,
    ) -> NetLayout:
        """Given lists; the span ends are added to the rings if missing, and on an axis whose
        joints are rings (a route) its joints (a ring within 1e-6 of the span from one moves onto it)."""
        s0, s1 = tube.span
        rings = _numbers("s_rings", s_rings, f"a non-empty list of finite arc lengths in [{s0:g}, {s1:g}]", MAX_RINGS)
        angles = _numbers("u_stringers_deg", stringers_deg, "a non-empty list of finite angles", MAX_STRINGERS)
        if rings.size == 0 or not np.all(np.isfinite(rings)):
            raise ParameterError(f"s_rings must be finite arc lengths in [{s0:g}, {s1:g}], got {_shown(rings)}")
        if rings.min() < s0 - 1e-9 * (s1 - s0) or rings.max() > s1 + 1e-9 * (s1 - s0):
            raise ParameterError(
                f"s_rings must lie in the span [{s0:g}, {s1:g}], got [{rings.min():g}, {rings.max():g}]"
            )
        rings = np.unique(np.clip(np.concatenate([[s0, s1], rings]), s0, s1))
        if tube.axis.rings_at_joints:  # a route's line-bend joints are always rings (faces lie on one piece)
            joints = np.array([s for s, _ in tube.axis.joints], dtype=float)
            if joints.size:
                far = np.min(np.abs(rings[:, None] - joints[None, :]), axis=1) >= 1e-6 * (s1 - s0)
                rings = np.unique(np.concatenate([rings[far], joints]))
        if np.min(np.diff(rings)) < 1e-6 * (s1 - s0):
            raise ParameterError("s_rings must be distinct (at least 1e-6 of the span apart)")
        if angles.size == 0 or not np.all(np.isfinite(angles)):
            raise ParameterError(f"u_stringers_deg must be a non-empty list of finite angles, got {_shown(angles)}")
        angles = np.unique(np.round(np.mod(angles, 360.0), 12))
        if len(angles) > 1 and np.min(np.diff(np.concatenate([angles, [angles[0] + 360.0]]))) < 1e-6:
            raise ParameterError("u_stringers_deg must be distinct angles (mod 360)")
        _face_count(len(rings), len(angles))
        return cls(tuple(map(float, rings)), tuple(map(float, angles)))

    @property
    def faces_per_tube(self) -> int:
        return (len(self.s_rings) - 1) * len(self.stringers_deg)

    def panel_bounds(self, seams: Sequence[int], rings: Sequence[int] | None = None) -> tuple[list[int], list[int]]:
        """The seam stringers and bounding rings of panels on this layout, checked.

        Args:
            seams: stringer indices the wall is split along (at least one).
            rings: ring indices bounding the panels (None: every ring); the end rings are always added.

        Returns:
            (the seams, sorted and distinct; the rings, sorted and distinct, end rings included).

        Raises:
            ParameterError: an index outside the layout, naming the range.
        """
        n_s, n_r = len(self.stringers_deg), len(self.s_rings)
        if not seams or any(not 0 <= j < n_s for j in seams):
            raise ParameterError(f"seams must be one or more stringer indices in [0, {n_s - 1}], got {list(seams)}")
        if rings is not None and any(not 0 <= i < n_r for i in rings):
            raise ParameterError(f"rings must be ring indices in [0, {n_r - 1}], got {sorted(set(rings))}")
        chosen = sorted(set(range(n_r) if rings is None else rings) | {0, n_r - 1})
        return sorted(set(seams)), chosen


def equal_rings(tube: CurvatureLineSurface, rings: int, stringers: int = 1) -> np.ndarray:
    """The arc lengths of ``rings`` ring frames equally spaced over the span: on an open axis
    the ends included, s0 + j L / (N - 1), j = 0..N-1; on a closed axis N distinct rings,
    s0 + j L / N, j = 0..N (the last, at s1, is the first one again: the closing ring). A
    ParameterError names ``rings`` (at least 2: a closed tube needs a ring besides the closing one)."""
    closed = tube.axis.closed
    _whole("rings", rings, 2, MAX_RINGS)
    _face_count(rings + closed, stringers)
    return np.linspace(*tube.span, rings + 1 if closed else rings)


def equal_stringers(stringers: int) -> np.ndarray:
    """The angles of ``stringers`` stringers equally spaced round: 360 j / M deg, j = 0..M-1."""
    _whole("stringers", stringers, 1, MAX_STRINGERS)
    return 360.0 * np.arange(stringers) / stringers


def _whole(name: str, value: object, least: int, most: int) -> None:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or not least <= value <= most:
        raise ParameterError(f"{name} must be a whole number >= {least} and <= {most}, got {value!r:.80}")


def _face_count(rings: int, stringers: int) -> None:
    faces = (int(rings) - 1) * int(stringers)
    if faces > MAX_FACES:
        raise ParameterError(
            f"the layout has (rings - 1) x stringers = {rings - 1} x {stringers} = {faces} faces; "
            f"at most {MAX_FACES} are allowed"
        )


def _numbers(name: str, values: object, wanted: str, most: int) -> np.ndarray:
    """A list of reals as a float array, or a ParameterError naming ``name``."""
    try:
        items = list(values)  # type: ignore[call-overload]
    except TypeError:
        items = None
    if items is None or isinstance(values, (str, bytes)) or any(isinstance(v, (bool, np.bool_)) for v in items):
        raise ParameterError(f"{name} must be {wanted}, got {values!r:.80}")
    if len(items) > most:
        raise ParameterError(f"{name} has {len(items)} entries; at most {most} are allowed")
    try:
        array = np.asarray(items, dtype=float) if items else np.zeros(0)
    except (TypeError, ValueError):
        array = None
    if array is None or array.ndim != 1:
        raise ParameterError(f"{name} must be {wanted}, got {values!r:.80}")
    return array


def _shown(values: np.ndarray) -> str:
    text = "[" + ", ".join(f"{v:g}" for v in values[:8]) + (", ..." if len(values) > 8 else "") + "]"
    return text


def stringer_parameters(stringers_deg: Sequence[float], u_at: Callable[[float], Any]) -> list[float]:
    """OCCT u cuts [u_0 = 0, u_1, ..., 2 pi] for a surface whose u = 0 is the first stringer."""
    cuts = [0.0] + [float(u_at(a)) for a in stringers_deg[1:]] + [2 * math.pi]
    return cuts
