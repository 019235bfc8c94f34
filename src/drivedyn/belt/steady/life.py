"""Belt life by rib fatigue: B10 in hours from a damage sum over the duty cycle, with each pulley's
and each duty row's share of the damage.

The supplier's model is proprietary; the form and constants are a published fit to Gates
accessory-drive reports (kaydgn/MFSim, js/fead-core.js, "FATIGUE", MIT licence; a fit, not the
supplier's model), the model's ``duty_cycle.life``:

    D = [sum_i w_i d_e,i^-m] x [sum_rows share x v / L] x (T_design / ribs)^q x 2^((theta - theta_ref) / halving)
    B10 = C / D   (hours)

d_e the effective diameter (mm), w = 1 on grooved and ``back_side_weight`` on back-side pulleys,
v the belt speed (m/s), L the nominal effective length (m), T_design the design tension (N), theta
the temperature (deg C: the life halves every ``halving`` degrees). A pulley's share of the damage
is its w d_e^-m normalised, a row's share its share x v normalised.

Expected error (the source's own measurement, and tests/belt/test_supplier_report.py): within
2.4 % RMS of the printed B10 on five reports whose pulleys all lie in 79.6-175 mm effective diameter;
drives with a 55-59 mm alternator pulley come out about 0.55 x the printed life (the d^-5.6 law
overcounts small pulleys), and one report in range (AG00894) 1.9 x off. ``in_range`` says whether
the drive lies in the fit's range.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..geometry.catalogue import effective_diameters

#: effective diameters (m) of the reports the fit was measured on
FIT_RANGE = (79.6e-3, 175.0e-3)


@dataclass(frozen=True)
class BeltLife:
    b10_hours: float
    pulley_share: dict         # pulley -> share of the rib-fatigue damage
    row_share: list            # per duty row, its share of the damage
    in_range: bool             # every effective diameter within FIT_RANGE
    out_of_range: list         # pulleys outside it


def belt_life(model, design_tension: float, belt_speeds) -> BeltLife:
    """B10 of the model's belt over its duty cycle; ``belt_speeds`` (m/s) per duty row.

    Summed in logarithms (each factor can leave double precision on its own where the others bring
    it back); a B10 that is not a finite positive number of hours is refused, never judged."""
    from ...core.errors import ModelError

    dc, belt = model.duty_cycle, model.belt
    fit = dc.life
    d_mm = effective_diameters(model) * 1e3
    log_geo = {p.name: (math.log(fit.back_side_weight) if p.side == "back" else 0.0) - fit.exponent * math.log(d)
               if (p.side != "back" or fit.back_side_weight > 0) else -math.inf
               for p, d in zip(model.pulleys, d_mm)}
    L = belt.effective_length
    # each row at its own temperature (the cycle's where a row gives none)
    # (a row of no share, or no belt speed, carries no damage: log 0 = -inf)
    log_rows = [math.log(r.share * v / L) + math.log(2.0) * ((r.temperature if r.temperature is not None
                                                             else dc.temperature) - fit.reference_temperature) / fit.halving
                if r.share * v > 0 else -math.inf
                for r, v in zip(dc.rows, belt_speeds)]
    log_g, log_r = _log_sum(log_geo.values()), _log_sum(log_rows)
    log_d = log_g + log_r + fit.tension_exponent * math.log(design_tension / belt.ribs)
    log_b10 = math.log(fit.constant) - log_d
    if not math.log(1e-30) < log_b10 < math.log(1e30):    # a damage sum of 0 or past double precision too
        val = f"{math.exp(log_b10):.4g}" if abs(log_b10) < 700 else f"e^{log_b10:.4g}"
        raise ModelError(f"the belt-life fit gives B10 = {val} h, outside 1e-30..1e30 h: the drive lies outside the "
                         f"fit's domain (design tension {design_tension:.4g} N over {belt.ribs} ribs, effective "
                         f"diameters {min(d_mm):.4g}-{max(d_mm):.4g} mm; steady/life.py)", field="duty_cycle.life")
    # the range as the source prints it, to its 0.1 mm (AG0868's crank, 175.01 mm, lies in it)
    out = [p.name for p, d in zip(model.pulleys, d_mm) if not FIT_RANGE[0] * 1e3 - 0.05 <= d <= FIT_RANGE[1] * 1e3 + 0.05]
    return BeltLife(math.exp(log_b10), {n: math.exp(x - log_g) for n, x in log_geo.items()},
                    [math.exp(x - log_r) for x in log_rows], not out, out)


def _log_sum(logs) -> float:
    """log(sum(exp(x))) of finite or -inf logarithms, without leaving double precision."""
    logs = list(logs)
    top = max(logs)
    if top == -math.inf:
        return top
    return top + math.log(sum(math.exp(x - top) for x in logs))
