"""Curvature expressions typed into spec files are parsed, never executed."""

import math

import numpy as np
import pytest

from tubecad import CustomCurvature, ExpressionError, ParameterError
from tubecad.curves.expression import compile_expression


@pytest.mark.parametrize(
    "text, expected",
    [
        ("10 / s", lambda s: 10 / s),
        ("0.02 + 1e-5 * s", lambda s: 0.02 + 1e-5 * s),
        ("-s ** 2 / 4", lambda s: -(s**2) / 4),
        (
            "sqrt(s) * exp(-s / 100) + cos(pi * s) * e",
            lambda s: np.sqrt(s) * np.exp(-s / 100) + np.cos(np.pi * s) * np.e,
        ),
        (
            "abs(sin(s)) + ln(s) - log10(s) + atan(s)",
            lambda s: np.abs(np.sin(s)) + np.log(s) - np.log10(s) + np.arctan(s),
        ),
        ("3", lambda s: 3.0 + 0 * s),
    ],
)
def test_arithmetic_is_evaluated_like_numpy(text, expected):
    s = np.linspace(1.0, 50.0, 17)
    assert np.allclose(compile_expression(text)(s), expected(s), rtol=1e-15, atol=0)


@pytest.mark.parametrize(
    "text, says",
    [
        ("__import__('os').system('echo pwned')", "function"),
        ("s.__class__", "attribute access"),
        ("os", "unknown name 'os'"),
        ("(lambda: 1)()", "function"),
        ("[x for x in s]", "ListComp"),
        ("s[0]", "Subscript"),
        ("'abc'", "only numbers"),
        ("9 ** 9 ** 9", "nested powers"),
        ("s ** 1000", "exponent 1000 is out of range"),
        ("s ^ 2", "write a ** b"),
        ("sin(s, 2)", "exactly one argument"),
        ("exp(x=s)", "exactly one argument"),
        ("s if s else 1", "IfExp"),
        ("1 +", "not a valid expression"),
        ("(" * 300 + "s" + ")" * 300, "not a valid expression"),
        ("-" * 900 + "s", "syntax nodes"),
        ("s+" * 250 + "s", "syntax nodes"),
        ("s" * 1001, "at most 1000"),
        ("1j * s", "only numbers"),
        ("True", "only numbers"),
    ],
)
def test_unsafe_or_malformed_expressions_are_refused(text, says):
    with pytest.raises(ExpressionError, match=None) as info:
        compile_expression(text)
    assert says in str(info.value)
    assert str(info.value).startswith("k")


def test_non_finite_curvature_is_reported_with_where():
    with pytest.raises(ParameterError, match=r"k\(s\) is not finite at s = "):
        CustomCurvature("1 / (s - 500)", 10.0, (0.0, 1000.0))


def test_refused_text_has_no_side_effect(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ExpressionError):
        CustomCurvature("__import__('pathlib').Path('pwned').touch()", 0.0, (1.0, 2.0))
    assert not (tmp_path / "pwned").exists()
    assert math.isfinite(CustomCurvature("1 / s", 0.0, (1.0, 2.0)).curvature(1.5))
