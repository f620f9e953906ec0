"""tubecad: tubular surfaces parameterised by their lines of curvature.

The pipeline, one folder per stage:

- :mod:`tubecad.curves`: axes from a natural equation k(s) and an elevation angle;
- :mod:`tubecad.surface`: the curvature-line tube S(u, s), its forms and regularity;
- :mod:`tubecad.export`: pictures (and, later, CAD files);
- :mod:`tubecad.interfaces`: spec files, reports and the ``tubecad`` command line.
"""

from importlib import import_module

#: public name -> the module that defines it; imported on first use (PEP 562), so that
#: ``tubecad --help`` and a Ctrl-C at start-up load no numpy, scipy or OCCT
_PUBLIC = {
    "SlopeCurve": ".curves", "LogSpiral": ".curves", "Helix": ".curves", "Clothoid": ".curves",
    "CircleInvolute": ".curves", "CustomCurvature": ".curves",
    "CurvatureLineTube": ".surface", "FundamentalForms": ".surface", "paper_tube": ".examples",
    "TubecadError": ".errors", "ParameterError": ".errors", "ExpressionError": ".errors",
    "RegularityError": ".errors", "SpecError": ".errors",
}  # fmt: skip

__all__ = list(_PUBLIC)


def __getattr__(name: str):
    if name in _PUBLIC:
        value = getattr(import_module(_PUBLIC[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tubecad' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))
