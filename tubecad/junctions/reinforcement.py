"""Area replacement at a branch opening, in the style of ASME VIII-1 UG-37: a geometric aid
for the designer, **not a code certification** (welds, corrosion allowance, the factor F off
the longitudinal plane, impact and fatigue rules are not in it).

With the design pressure P, the allowable stresses S (shell), S_n (nozzle), S_p (pad), the
joint efficiency E = E1 = 1 and the strength ratios f_r2 = min(S_n / S, 1), f_r4 = min(S_p / S, 1):

    t_r  = P R / (S - 0.6 P),  t_rn = P R_n / (S_n - 0.6 P)     (UG-27(c)(1), inside radii R, R_n)
    A    = d t_r                                                (required; F = 1, set-on nozzle)
    A1   = max(d, 2 (t + t_n)) (t - t_r)                        (excess in the shell)
    A2   = min(5 (t_n - t_rn) f_r2 t, 2 (t_n - t_rn)(2.5 t_n + t_e) f_r2)   (in the nozzle wall)
    A5   = (min(D_p, 2 L) - d - 2 t_n) t_e f_r4,  L = max(d, R_n + t_n + t)   (in the pad, within the limit)

and the opening is reinforced when A1 + A2 + A5 >= A. Here d, the opening's finished
diameter, is the bore saddle's extent along the main tube's axis (max - min of s_A on the
main inner surface): 2 R_n for a square branch, 2 R_n / sin(angle) for an oblique one, so
the longest chord of the opening, measured, not assumed.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from tubecad.core.errors import ParameterError
from tubecad.junctions.saddle import SaddleCurve

DISCLAIMER = "a geometric aid in the style of ASME VIII-1 UG-37, not a code certification"


@dataclass(frozen=True)
class AreaReplacement:
    """The figures of :func:`area_replacement` (lengths in the model's unit, areas its square)."""

    d: float
    t_r: float
    t_rn: float
    required: float
    shell: float
    nozzle: float
    pad: float
    note: str = DISCLAIMER

    @property
    def available(self) -> float:
        return self.shell + self.nozzle + self.pad

    @property
    def adequate(self) -> bool:
        return self.available >= self.required

    def as_dict(self) -> dict[str, object]:
        """For report.json: the figures, their sum and the verdict, with the disclaimer."""
        return {**asdict(self), "available": self.available, "adequate": self.adequate}


def opening_diameter(bore_saddle: SaddleCurve) -> float:
    """d: the extent of the bore's saddle along the main axis, max s_A - min s_A (each
    refined between the samples: :meth:`SaddleCurve.extent`)."""
    low, high = bore_saddle.extent(bore_saddle.main_s)
    return high - low


def area_replacement(
    bore_saddle: SaddleCurve,
    *,
    shell_radius: float,
    shell_thickness: float,
    nozzle_radius: float,
    nozzle_thickness: float,
    pressure: float,
    stress: float,
    nozzle_stress: float | None = None,
    pad_diameter: float = 0.0,
    pad_thickness: float = 0.0,
    pad_stress: float | None = None,
    key: str = "branches",
) -> AreaReplacement:
    """The area-replacement figures of the opening whose bore saddle is ``bore_saddle``
    (radii inside, thicknesses nominal; stresses and pressure in one unit). See the module."""
    values = {
        "shell_radius": shell_radius,
        "shell_thickness": shell_thickness,
        "nozzle_radius": nozzle_radius,
        "nozzle_thickness": nozzle_thickness,
        "pressure": pressure,
        "stress": stress,
    }
    for name, value in values.items():
        if not value > 0:
            raise ParameterError(f"{key}.{name} must be > 0, got {value!r:.40}", key=f"{key}.{name}")
    s_n = stress if nozzle_stress is None else nozzle_stress
    s_p = stress if pad_stress is None else pad_stress
    if not (s_n > 0.6 * pressure and stress > 0.6 * pressure):
        raise ParameterError(
            f"{key}.pressure must be below 0.6 x the allowable stresses (UG-27)", key=f"{key}.pressure"
        )
    d = opening_diameter(bore_saddle)
    t, t_n, t_e = shell_thickness, nozzle_thickness, pad_thickness
    t_r = pressure * shell_radius / (stress - 0.6 * pressure)
    t_rn = pressure * nozzle_radius / (s_n - 0.6 * pressure)
    f_r2, f_r4 = min(s_n / stress, 1.0), min(s_p / stress, 1.0)
    required = d * t_r
    shell = max(d, 2 * (t + t_n)) * max(t - t_r, 0.0)
    nozzle = max(min(5 * (t_n - t_rn) * f_r2 * t, 2 * (t_n - t_rn) * (2.5 * t_n + t_e) * f_r2), 0.0)
    limit = max(d, nozzle_radius + t_n + t)  # UG-40: the reinforcement limit each side of the centre line
    pad = max(min(pad_diameter, 2 * limit) - d - 2 * t_n, 0.0) * t_e * f_r4 if t_e > 0 else 0.0
    return AreaReplacement(d, t_r, t_rn, required, shell, nozzle, pad)
