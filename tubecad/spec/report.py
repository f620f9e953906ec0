"""report.json: the report of a build (:mod:`tubecad.design.report`), under the spec's names."""

from tubecad.design.report import (
    DEFAULT_NS,
    DEFAULT_NU,
    build_report,
    canal_report,
    stiffener_report,
    to_json,
    tube_report,
)

__all__ = ["DEFAULT_NS", "DEFAULT_NU", "build_report", "canal_report", "stiffener_report", "to_json", "tube_report"]
