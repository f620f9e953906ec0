"""A design's shop package: the one path of ``tubecad shop``.

Each design computes its own package (:meth:`~tubecad.design.wall.WallDesign.shop`,
:meth:`~tubecad.design.junction.JunctionDesign.shop`) and the package writes itself into a
folder (the :class:`ShopPackage` protocol), so the command never asks which kind it holds:

- :class:`WallShop`: a wall's stiffeners and panels (:func:`tubecad.shop.package.shop_data`:
  web pieces nested on plates, flanges, bending tables, marking lines, developments, pin jigs)
  written by :func:`tubecad.shop.writer.write_shop`;
- :class:`~tubecad.design.junction_shop.JunctionShop`: each branch's cutting template, its
  opening's template, its bevel basis and its pad's development, and the junction's stopped
  stiffeners' package.

Errors speak Python terms and carry the stage ``fabrication`` (a plate too small, a joint
outside its stiffener) or ``templates`` with the branch's index.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from tubecad.shop.package import ShopData


class ShopPackage(Protocol):
    """What the shop gets for one design, computed and ready to write."""

    def write(self, folder: Path, name: str) -> dict[str, Any]:
        """Write the package into ``folder`` (a staging folder: the caller moves it into place)
        with ``name`` in its files' titles; returns the index (also written as index.json)."""
        ...


@dataclass
class WallShop:
    """A wall's shop package (:class:`tubecad.shop.package.ShopData`)."""

    data: ShopData

    def write(self, folder: Path, name: str) -> dict[str, Any]:
        """:func:`tubecad.shop.writer.write_shop`."""
        from tubecad.shop.writer import write_shop

        return write_shop(self.data, folder, name)
