"""Stiffeners and seams on the curvature-line net: lines, stiffener solids, flat patterns."""

from .lines import CurvatureLine, lines_compound, net_lines, polylines_csv, polylines_json

__all__ = ["CurvatureLine", "net_lines", "lines_compound", "polylines_csv", "polylines_json"]
