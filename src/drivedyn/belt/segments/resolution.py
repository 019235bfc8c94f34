"""What the belt's discretisation leaves in the numbers a segment run reports: the summary's
``discretisation`` (segments, their length, the rule that set the count, the chordal error, the
grid damper), the rule's measured accuracy as an error estimate, and the resolution check (a second
run at fewer segments). The count itself and the measurements behind the rule are in
geometry/segment_count.py.
"""
from __future__ import annotations

import math

from ...core.errors import ModelError
from ..model import MAX_AUTO
from ..geometry.segment_count import MIN_SEGMENTS, WRAP_MIN_DEG, auto_segments, chord_sag


def discretisation(model, sysm) -> dict:
    """What the summary reports of the resolution: segments, their length, the rule, the
    segments on each wrap's shortest and the polygon's speed error (taken out of slip)."""
    lay, l = sysm.layout, sysm.init.seg_length
    resolved_ = [j for j in range(len(model.pulleys)) if math.degrees(lay.wrap[j]) >= WRAP_MIN_DEG]
    per_wrap = {model.pulleys[j].name: float(lay.wrap[j] * model.pulleys[j].radius / l) for j in resolved_}
    short = min(per_wrap, key=per_wrap.get) if per_wrap else None
    r_min = min(p.radius for p in model.pulleys)
    try:
        n_auto, why = auto_segments(model, lay)
    except ModelError:          # "auto" would take more than MAX_AUTO: no rule to compare with
        n_auto, why = None, None
    rule = why if model.belt.segments == "auto" else "given (belt.segments)"
    sag = chord_sag(model, lay, l)
    return {"segments": int(sysm.n), "segment_length": float(l), "rule": rule,
            "shortest_wrap": short, "segments_on_shortest_wrap": per_wrap[short] if short else None,
            "unresolved_wraps": {p.name: float(math.degrees(lay.wrap[j])) for j, p in enumerate(model.pulleys)
                                 if j not in resolved_},
            "chordal_speed_error": float(l * l / (12 * r_min * r_min)),
            "chord_sag_to_depth": sag if math.isfinite(sag) else None,     # None: a slack belt
            "slip_measured_against": "the chain's rolling radius (polygon effect removed)",
            "grid_damping": _grid_damping(model, sysm),
            "estimate": rule_estimate(model, int(sysm.n), n_auto)}


def _grid_damping(model, sysm) -> dict:
    """The bending damper that damps the chain's grid-scale rotation mode (system.GRID_ZETA), and
    whether it or the belt's own bending damping is in use."""
    from .system import GRID_ZETA, grid_damping

    # what the built system uses (system._build: the larger of the two, at the placement's
    # tension; sysm.init.tension is the settled one)
    used = float(sysm.belt.bb[0])
    in_use = used > model.belt.bending_damping / sysm.init.seg_length
    return {"bending_damper": used if in_use else float(grid_damping(model.belt, sysm.init)),
            "damping_ratio": GRID_ZETA, "in_use": bool(in_use),
            "note": "damps neighbouring segments turning against each other (a mode of the segment chain, not "
                    "of the belt); its loss, counted under bending_damping, falls as the segment length squared"}


#: the "auto" rule's accuracy per friction law: the largest error of a pulley's mean slip (a
#: fraction: 1.9e-4 is 0.019 percentage points) and of a span's tension minimum or maximum
#: (relative), measured on examples/fead-runup.toml's drive held at 1000 / 3000 / 5000 rpm with its
#: 2nd/4th orders against 4 x the "auto" segments (semi-implicit, unscaled;
#: benchmarks/bench_fead_defaults.py; the figures are in docs/belt-drive.md, Resolution):
#: elastic-plastic at 333 segments, the implicit scheme at its default step (38.5 / 22.7 / 13.5
#: us), minima within 2.4 / 1.6 / 3.0 %, maxima 2.0 / 0.9 / 2.7 %, slips 0.019 / 0.005 / 0.002
#: points; Threlfall at 666 (semi-implicit), minima within 1.5 / 4.5 / 2.5 %, maxima 0.5 / 2.6 /
#: 1.4 %, slips 0.016 / 0.013 / 0.009 points
RULE_ACCURACY = {"elastic-plastic": (1.9e-4, 0.030), "threlfall": (1.6e-4, 0.045)}
#: the share of the losses at the "auto" count that is discretisation (the polygon's landing
#: impacts): the losses less their l^2 extrapolation, over the losses. Measured (implicit scheme,
#: elastic-plastic): examples/fead-runup.toml's drive held with its orders, 333 against 1332
#: segments, 43.8 / 132.4 / 242.6 W against 37.7 / 105.3 / 180.8 W at 1000 / 3000 / 5000 rpm
#: (15 / 22 / 27 %); the 5PK held at 800 rad/s (Threlfall, semi-implicit), 424 against 848
#: segments, 12.1 against 9.5 W (28 %)
LOSS_ACCURACY = 0.3
#: a run-up's span tension error near a resonance at the "auto" count: examples/fead-runup.toml's
#: run-up at 333 segments against 666, the largest bin difference (docs/belt-drive.md)
RUNUP_ACCURACY = 0.082


def rule_estimate(model, n: int, n_auto) -> dict:
    """The discretisation error a run states without a resolution check: at or above the segments
    "auto" takes, the rule's accuracy as measured on the calibration drive (RULE_ACCURACY), not
    this drive's (``simulation.resolution_check`` measures that); below them, none."""
    law = model.friction.law
    if n_auto is None:
        return {"method": "none", "unavailable": f"\"auto\" would take more than {MAX_AUTO} segments: the error "
                                                 "is not known; set simulation.resolution_check = true"}
    if n < n_auto:
        return {"method": "none: fewer segments than \"auto\" takes", "auto_segments": n_auto,
                "unavailable": f"{n} segments against the {n_auto} of \"auto\": the error is not known; set "
                               "belt.segments = \"auto\" or simulation.resolution_check = true"}
    slip, tension = RULE_ACCURACY[law]
    out = {"method": f"the \"auto\" rule's accuracy ({law} friction), measured on examples/fead-runup.toml's "
                     "drive at 1000-5000 rpm against 4 x the segments; not this drive's: "
                     "simulation.resolution_check measures that",
           "auto_segments": n_auto, "slip_largest": slip, "tension_relative_largest": tension,
           "power_loss_relative": LOSS_ACCURACY,
           "power_loss_method": "the \"auto\" rule's: the losses less their limit in the segment count (l^2 "
                                "extrapolation), over the losses, at most 15 / 22 / 27 % on "
                                "examples/fead-runup.toml's drive held at 1000 / 3000 / 5000 rpm and 28 % on the "
                                "5PK held at 800 rad/s",
           "power_loss_note": "the losses read high (the contact damping of the polygon's landing impacts, whose "
                              "share falls as l^2), and power.efficiency low: fead-runup's drive held at 3000 rpm "
                              "loses 132 W at 333 segments against 105 W at 1332"}
    if model.output.runup_bin is not None:
        # docs/belt-drive.md, Engine accessory drives: the run-up against 666 segments
        out["runup_tension_relative_largest"] = RUNUP_ACCURACY
        out["runup_note"] = ("measured at held speeds: a run-up's bins near a resonance converge more slowly "
                             f"(examples/fead-runup.toml's run-up at 333 segments: span minima up to "
                             f"{100 * RUNUP_ACCURACY:.1f} % off 666 segments at 3875-4375 rpm, within 4.6 % elsewhere)")
    return out


#: the resolution check's coarser run, as a share of the segments, and its accuracy targets (the
#: accessory-drive targets: slip within 0.03 points, span tension within 3 %)
CHECK_RATIO = 0.7
SLIP_TARGET = 3e-4
TENSION_TARGET = 0.03


def _quantities(s: dict) -> dict:
    """What the check compares: each pulley's slip and each span's tension min/mean/max; for a
    run-up the largest slip and the extreme tensions of any crank-speed bin."""
    ru = s.get("runup")
    out = {}
    if ru:
        for p, v in ru["slip"].items():
            out[("slip", p)] = max((abs(x) for x in v if x == x), default=float("nan"))
        for sp, v in ru["span_tension_min"].items():
            out[("tension_min", sp)] = min((x for x in v if x == x), default=float("nan"))
        for sp, v in ru["span_tension_max"].items():
            out[("tension_max", sp)] = max((x for x in v if x == x), default=float("nan"))
        return out
    for p, e in s["pulleys"].items():
        out[("slip", p)] = e["slip"]
    for sp, e in s["spans"].items():
        for k in ("tension_min", "tension_mean", "tension_max"):
            out[(k, sp)] = e[k]
    return out


def _losses(s: dict) -> dict:
    """The steady window's losses by mechanism (W); none for a run-up."""
    return {} if s.get("runup") else dict(s.get("power", {}).get("losses", {}))


def check(model, result, run) -> None:
    """The resolution check: ``run`` the model again at CHECK_RATIO x its segments and put the
    change of each compared quantity, over (1 / CHECK_RATIO - 1), into
    ``summary.discretisation.estimate`` as its error estimate: first order assumed, which over-
    rather than under-states the error of quantities that converge faster (the chordal and wrap
    effects are of second and higher order in the segment length). The steady window's losses get
    a second-order estimate (``power_loss``, W). A ``unconverged-resolution`` diagnostic when a
    slip or tension estimate exceeds its target."""
    n = result.summary["belt"]["segments"]
    n2 = max(MIN_SEGMENTS // 2, int(round(CHECK_RATIO * n)))
    coarse = model.model_copy(update={
        "belt": model.belt.model_copy(update={"segments": n2}),
        "simulation": model.simulation.model_copy(update={"resolution_check": False}),
        "output": model.output.model_copy(update={"segments": [], "frames": 1})})   # what it does not compare
    from ...core.errors import SolverError

    try:
        other = run(coarse)
    except (ModelError, SolverError) as exc:     # too coarse to build, or it failed: say so, keep the run
        result.summary.setdefault("discretisation", {})["estimate"] = {
            "method": f"a run at {n2} segments ({CHECK_RATIO:g} x)", "coarse_segments": n2,
            "unavailable": str(exc).splitlines()[0]}
        return
    a, b = _quantities(result.summary), _quantities(other.summary)
    factor = 1.0 / (n / n2 - 1.0)
    slip, tension = {}, {}
    worst_slip, worst_t = (0.0, ""), (0.0, "")
    for key, va in a.items():
        vb = b.get(key, float("nan"))
        err = abs(va - vb) * factor
        if key[0] == "slip":
            slip[key[1]] = err
            if err > worst_slip[0]:
                worst_slip = (err, key[1])
        else:
            rel = err / abs(va) if va else float("nan")
            tension.setdefault(key[1], {})[key[0]] = rel
            if rel > worst_t[0]:
                worst_t = (rel, f"{key[1]} {key[0].replace('_', ' ')}")
    disc = result.summary.setdefault("discretisation", {})
    disc["estimate"] = {
        "method": f"change from a run at {n2} segments ({CHECK_RATIO:g} x), times {factor:.3g} (first order assumed)",
        "coarse_segments": n2, "slip": slip, "span_tension_relative": tension,
        "slip_largest": worst_slip[0], "tension_relative_largest": worst_t[0],
        "coarse_status": other.status}
    # The losses: the contact damping holds the polygon's landing impacts, whose share falls as
    # l^2 (examples/fead-runup.toml's drive held at 3000 rpm: 129 / 98 / 90 W at 333 / 666 / 1332
    # segments unscaled, about 87 W converged), so their change is extrapolated at second order;
    # the first-order factor overstated that one 2.6 times (and the 5PK's, mostly friction, 2.9
    # times: tests/belt/test_resolution.py).
    la, lb = _losses(result.summary), _losses(other.summary)
    if la and lb:
        f2 = 1.0 / ((n / n2) ** 2 - 1.0)
        loss = {k: abs(la[k] - lb[k]) * f2 for k in la if k in lb}
        total = sum(abs(v) for v in la.values())
        disc["estimate"]["power_loss"] = loss
        disc["estimate"]["power_loss_relative"] = sum(loss.values()) / total if total > 0 else float("nan")
        disc["estimate"]["power_loss_method"] = f"change times {f2:.3g} (second order: the landing impacts)"
    from ...core.results import unit_map
    from ..dynamics.outputs import UNITS

    result.units = unit_map(result.summary, UNITS)
    if worst_slip[0] > SLIP_TARGET:
        result.diagnose("unconverged-resolution", f"the slip of pulley {worst_slip[1]} changes by an estimated "
                        f"{100 * worst_slip[0]:.3f} points with the segment count ({n} against {n2} segments)",
                        "discretisation.estimate.slip_largest", worst_slip[0], SLIP_TARGET, "1")
    if worst_t[0] > TENSION_TARGET:
        result.diagnose("unconverged-resolution", f"the {worst_t[1]} changes by an estimated {100 * worst_t[0]:.1f} % "
                        f"with the segment count ({n} against {n2} segments)",
                        "discretisation.estimate.tension_relative_largest", worst_t[0], TENSION_TARGET, "1")
