"""A library error told in a spec's terms (issue 42): the libraries (tubecad.fem, tubecad.shop)
name their own parameters, ``surface = 'inner' needs a wall`` with ``key="surface"``; the spec
layer, where it calls them, adds the section the value came from: ``spec.toml: [mesh] surface
= 'inner' needs a wall``, key ``mesh.surface``.

Light on purpose (no numpy, no OCCT): the commands' checks import it before anything is built.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from tubecad.core.errors import SpecError, TubecadError


def within(section: str, exc: TubecadError, default: str | None = None) -> str:
    """The spec key of an error about ``section``: its own key (made ``section.key`` if it
    names a key alone), else ``default`` (within the section too), else the section."""
    key = exc.key or default
    if key is None:
        return section
    return key if key == section or key.startswith(f"{section}.") else f"{section}.{key}"


def in_section(
    source: object, section: str, exc: TubecadError, *, label: str | None = None, key: str | None = None
) -> SpecError:
    """``exc`` as the spec's error: ``{source}: [section] {exc}`` (``[[section]]`` for an array
    of tables; ``label`` instead, e.g. ``[[branches]] #2``), its key ``key``, else the error's
    own :func:`within` the section."""
    from tubecad.spec.keys import ARRAY_SECTIONS

    where = label if label is not None else f"[[{section}]]" if section in ARRAY_SECTIONS else f"[{section}]"
    return SpecError(f"{source}: {where} {exc}", key=key if key is not None else within(section, exc))


def section_of(key: str | None, sections: Sequence[str]) -> str | None:
    """The first of ``sections`` that a library error's ``key`` belongs to: the section's own
    name (``stiffeners.side``) or one of its keys (:mod:`tubecad.spec.keys`: ``plate_size``,
    ``joints.ring_03``); None if none does (or there is no key)."""
    from tubecad.spec.keys import ARRAY_SECTIONS, EXTRA_SECTIONS

    head = (key or "").split(".")[0]
    for section in sections:
        if head and (head == section or head in (EXTRA_SECTIONS.get(section) or ARRAY_SECTIONS.get(section) or {})):
            return section
    return None


def spec_error(
    source: object,
    exc: TubecadError,
    sections: Sequence[str],
    default: str | None = None,
    aliases: Mapping[str, str] | None = None,
) -> SpecError:
    """The error ``exc`` of a library call in the spec's terms: in the section of its key
    (:func:`section_of` among ``sections``), else in ``default``; ``aliases`` maps a library
    parameter named otherwise than the spec's key onto that key (``panel_rings``:
    ``panels.rings``). With neither, the library's message after the spec's name."""
    key = exc.key
    if key is not None and aliases and key in aliases:
        return in_section(source, aliases[key].split(".")[0], exc, key=aliases[key])
    section = section_of(key, sections) or default
    if section is None:
        return SpecError(f"{source}: {exc}", key=key)
    return in_section(source, section, exc)
