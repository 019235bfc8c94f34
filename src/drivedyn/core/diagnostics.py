"""One status contract for every analysis: success, warning, failed, and the diagnostics behind it.

A run ends ``failed`` when it stopped (the partial results are kept), ``warning`` when it ran to
the end but at least one diagnostic says the result lies outside the model's valid regime or is
not converged, ``success`` otherwise. Each diagnostic names the quantity that was measured, its
value and the limit it crossed, so that a person (and a study) can judge how far off it is.

The codes are fixed and documented (docs/diagnostics.md); an analysis adds one with
``result.diagnose(code, text, quantity, value, limit, unit)``.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

#: every diagnostic code, with what it means (docs/diagnostics.md lists the same)
CODES = {
    "optimum-on-bound": "an optimisation's best design sits on a bound of a parameter's range (within 2 % of it): "
                        "the optimum may lie outside the design space",
    "model-accuracy": "the rotational belt model's span tension bands may sit further from the segment model's "
                      "than the stated share (its estimate in summary.discretisation.estimate): confirm them with "
                      "the segment model",
    "gross-slip": "a pulley slips grossly: the belt slides over the whole wrap instead of creeping",
    "contact-chatter": "belt segments bounce on a pulley: few wrapped segments in contact, peak normal forces far "
                       "above the static value",
    "contact-damping-depth": "the contact damping depth is far from the static penetration, so the contact "
                             "damping is far from its nominal value",
    "window-not-steady": "the quantities drift inside the steady window (or the slowest mode has not decayed): "
                         "the window means are not steady-state values",
    "energy-residual": "the energy balance (work in - dissipated - energy change) misses a large share of the work",
    "coarse-discretisation": "fewer belt segments than \"auto\" takes (the discretisation error is not known), or "
                             "segments long against a pulley radius or a wrap: chordal error in speeds, a wrap too "
                             "few segments hold",
    "unconverged-resolution": "the resolution check (simulation.resolution_check) estimates a discretisation error "
                              "in slip or span tension above its target: more segments",
    "kv-unstable": "the dynamic factor grows without bound (parametric instability of the linear mesh model) or "
                   "is not converged",
    "unconverged-periodic": "a periodic run-up's solution did not settle to a periodic one at some crank speeds "
                            "(the periodicity residual stayed above its tolerance)",
    "step-too-large": "the time step is too large for the integration method",
    "above-critical-speed": "the belt speed is at or above the span's critical speed: the span model does not apply",
    "parametric-resonance": "the span's operating point lies in a parametric-resonance region: its transverse "
                            "vibration grows (largest Floquet multiplier above 1)",
    "at-rest-drift": "a drive with no load moves away from its initial state",
    "tooth-separation": "the mesh force goes negative: the teeth would separate, the model assumes they stay in mesh",
    "table-extrapolated": "a pulley runs outside the speed range of its torque_speed table: its load is "
                          "extrapolated linearly from the table's last rows",
    "load-delivers-power": "a pulley loaded by a torque_speed table delivers net power into the belt: a load read "
                           "the wrong way round (the table's speed sign, or extrapolated through zero)",
    "tooth-jump": "a timing-belt tooth under the given torque climbs out of its groove (ratchets): the torque is at "
                  "or above the jump torque for the installation tension",
}

STATUSES = ("success", "warning", "failed")


@dataclass(frozen=True)
class Diagnostic:
    """One finding about a run: ``code`` (from CODES), a one-line ``text`` for a person, the
    ``quantity`` measured, its ``value``, the ``limit`` it crossed, and the ``unit`` of both."""

    code: str
    text: str
    quantity: str = ""
    value: float | None = None
    limit: float | None = None
    unit: str = ""

    def __post_init__(self):
        if self.code not in CODES:
            raise ValueError(f"unknown diagnostic code {self.code!r}")

    def to_dict(self) -> dict:
        d = asdict(self)
        for k in ("value", "limit"):
            v = d[k]
            d[k] = None if v is None or not math.isfinite(float(v)) else float(v)
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "Diagnostic":
        return cls(**{k: d.get(k) for k in ("code", "text", "quantity", "value", "limit", "unit")
                      if d.get(k) is not None})

    def line(self) -> str:
        """``code: text`` on one line, as the command line prints it."""
        return f"{self.code}: {self.text}"


def status_of(success: bool, diagnostics) -> str:
    """The one status word: failed (stopped), warning (ran, with diagnostics) or success."""
    if not success:
        return "failed"
    return "warning" if diagnostics else "success"
