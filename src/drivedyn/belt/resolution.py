"""The belt's resolution: how many segments (``belt.segments = "auto"``, the default) and what the
discretisation leaves in the numbers a run reports.

A chain of rigid segments of length l differs from the belt it stands for in two ways that reach
slip and span tension (tests/belt/test_resolution.py measures both against refined runs):

- polygon kinematics: the chain rolls on a pulley of radius r at about r (1 + l^2 / (12 r^2)).
  Slip is measured against the chain's own rolling radius (system.BeltSystem.rolling_radius), so
  this mean effect is no longer read as slip; what is left is the chordal impacts of segments
  entering and leaving the pulley, small while l is well below r.
- wrap resolution: a wrap holding few segments has its creep, its contact pressure and the span
  tensions at its ends sampled by those few. On the six-pulley accessory drive of
  examples/fead-runup.toml at 3000 rpm, the 45-degree tensioner wrap misreads its slip by 0.25
  points with 2.8 segments on it and by 0.004 with 5.6; the crank span's tension band is 10 %
  narrow at 150 segments against 600 (3 % at 300).

- chordal landing: a segment wrapped on a pulley of radius r stands off the circle by its chord
  sag l^2 / (8 r) at its ends, and each landing segment drops that far into the contact at the
  polygon frequency v / l. Where the sag is not small against the depth p to which the belt's
  tension presses it into the groove (contact pressure T / r, steady.penetration), landings shake
  the contact, the wraps carry their load in bursts and the drive's response at the engine orders
  is off by several per cent, converging only once the sag is a fraction of p. Measured on
  examples/fead-runup.toml's drive held at 3000 rpm with its orders (benchmarks/
  bench_fead_convergence.py): at sag / depth 0.87 (330 segments) span minima up to 9 % off 1320
  segments; at 0.25 (666) within 2.8 % of 1332 but one (4.5 %; with the tensioner arm held, or the
  alternator's one-way clutch replaced by a rigid rotor, every minimum within 1.7-1.9 % at
  660-666). A two-pulley drive's torsional mode, measured while running, is 3.3 % low at 4 m/s
  and 14 % low at 24 m/s at sag / depth 1.07, within 0.7 % at 0.27.

- the friction law decides how much of the landing must be resolved (the elastic-plastic law is
  the default): with Threlfall's law a
  landing segment slides at once (docs/belt-drive.md, "Friction's radius"), with the elastic-plastic
  law its pre-sliding displacement takes the landing up. The same drive with the elastic-plastic
  law at sag / depth 1.0 (333 segments) is within 2.0 / 2.8 / 3.2 % (span minima), 0.5 / 1.3 /
  2.4 % (maxima) and 0.016 / 0.003 / 0.007 points (slips) of 1332 segments at 1000 / 3000 / 5000
  rpm, where Threlfall's law at that sag is up to 9.4 % off.

"auto" takes the longest segment that puts WRAP_SEGMENTS on the shortest wrap, is at most
CHORD_RATIO of the smallest radius and whose chord sag is at most the friction law's sag ratio
(SAG_RATIO, SAG_RATIO_PRESLIDING) of the contact depth at the pretension on every pulley, with
MIN_SEGMENTS at least.
"""
from __future__ import annotations

import math

from ..errors import ModelError
from .layout import compute_layout
from .steady import penetration

#: segments on the shortest wrap (the wrap-resolution rule above)
WRAP_SEGMENTS = 6
#: largest segment length against the smallest pulley radius (chordal speed error 0.75 % before
#: the rolling-radius correction, impacts of entering segments small)
CHORD_RATIO = 0.3
MIN_SEGMENTS = 60
#: largest chord sag l^2 / (8 r) against the contact depth at the pretension (the chordal rule above)
SAG_RATIO = 0.25
#: ... with the elastic-plastic friction law, whose pre-sliding takes up the landings
SAG_RATIO_PRESLIDING = 1.0
#: wraps shorter than this (deg) are left out of the wrap rule: a 7-degree idler wrap would ask for
#: 3000 segments and carries almost no torque; discretisation.unresolved_wraps names them
WRAP_MIN_DEG = 20.0
#: "auto" never picks more
MAX_AUTO = 2000


def depths(model, layout) -> list[float]:
    """Per pulley, the contact depth p (m) at the pressure T / r of the belt's tension at rest: the
    pretension, or for a given unstretched length the tension stretching it over the drawn path
    (0 for a slack belt)."""
    T = model.belt.pretension
    if T is None:
        T = max(0.0, model.belt.axial_stiffness * (layout.length / model.belt.length - 1.0))
    c = model.contact
    return [float(penetration(T / p.radius, c.stiffness_quadratic, c.stiffness_linear)) for p in model.pulleys]


def chord_sag(model, layout, l) -> float:
    """The largest chord sag l^2 / (8 r) of segments of length l against the contact depth at rest
    over the pulleys (inf where the belt is slack)."""
    return max(l * l / (8.0 * p.radius * d) if d > 0 else math.inf for p, d in zip(model.pulleys, depths(model, layout)))


def sag_ratio(model) -> float:
    """The largest chord sag against the contact depth "auto" allows with the model's friction law."""
    return SAG_RATIO_PRESLIDING if model.friction.law == "elastic-plastic" else SAG_RATIO


def auto_segments(model, layout=None) -> tuple[int, str]:
    """The number of segments "auto" picks for ``model``, and the rule that set it."""
    lay = layout or compute_layout(model)
    radii = [p.radius for p in model.pulleys]
    arcs = [w * r if math.degrees(w) >= WRAP_MIN_DEG else math.inf for w, r in zip(lay.wrap, radii)]
    j = min(range(len(arcs)), key=arcs.__getitem__)
    k = min(range(len(radii)), key=radii.__getitem__)
    ratio = sag_ratio(model)
    sags = [math.sqrt(ratio * 8.0 * r * d) if d > 0 else math.inf for r, d in zip(radii, depths(model, lay))]
    q = min(range(len(sags)), key=sags.__getitem__)
    rules = [(arcs[j] / WRAP_SEGMENTS, f"{WRAP_SEGMENTS} segments on the shortest wrap ({model.pulleys[j].name}, "
                                       f"{math.degrees(lay.wrap[j]):.0f} deg on {radii[j] * 1e3:.3g} mm)"),
             (CHORD_RATIO * radii[k], f"segments at most {CHORD_RATIO:g} x the smallest radius ({model.pulleys[k].name}, "
                                      f"{radii[k] * 1e3:.3g} mm)"),
             (sags[q], f"chord sag at most {ratio:g} x the contact depth at rest ({model.pulleys[q].name}, "
                       f"{radii[q] * 1e3:.3g} mm)")]
    l, why = min(rules, key=lambda rule: rule[0])
    n = max(MIN_SEGMENTS, math.ceil(lay.length / l))
    if n > MAX_AUTO:
        raise ModelError(f"\"auto\" would need {n} segments ({why}), over the {MAX_AUTO} it may pick: give "
                         "belt.segments as a number", field="belt.segments")
    return n, why


def resolved(model):
    """``model`` with ``belt.segments`` a number ("auto" resolved); itself when it already is one."""
    if model.belt.segments != "auto":
        return model
    n, _ = auto_segments(model)
    for q in model.output.segments:
        if not 0 <= q < n:
            raise ModelError(f"index {q} outside 0..{n - 1} (belt.segments \"auto\" picks {n})", field="output.segments")
    return model.model_copy(update={"belt": model.belt.model_copy(update={"segments": n})})


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
    from ..errors import SolverError

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
    from ..results import unit_map
    from .simulate import UNITS

    result.units = unit_map(result.summary, UNITS)
    if worst_slip[0] > SLIP_TARGET:
        result.diagnose("unconverged-resolution", f"the slip of pulley {worst_slip[1]} changes by an estimated "
                        f"{100 * worst_slip[0]:.3f} points with the segment count ({n} against {n2} segments)",
                        "discretisation.estimate.slip_largest", worst_slip[0], SLIP_TARGET, "1")
    if worst_t[0] > TENSION_TARGET:
        result.diagnose("unconverged-resolution", f"the {worst_t[1]} changes by an estimated {100 * worst_t[0]:.1f} % "
                        f"with the segment count ({n} against {n2} segments)",
                        "discretisation.estimate.tension_relative_largest", worst_t[0], TENSION_TARGET, "1")
