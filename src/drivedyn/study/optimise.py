"""Design by optimisation: a study with ``mode = "optimise"`` (spec.Optimise).

Differential evolution (Storn & Price, J. Global Optim. 11 (1997) 341-359; scipy.optimize's
``differential_evolution``) over the ranged parameters, mapped to the unit cube (a log-scaled
parameter on its logarithm, an integer one rounded). Each generation is one batch of cases through
the study's own execution (the cache, the cluster, resume: a re-run evaluates nothing twice).
A design is judged by its objective and constraints on summary keys (a list, such as a run-up's
per-bin values, by its extreme). A design that did not run to its end (status failed, invalid,
error, lost) or misses a key is infeasible; constraints enter as a penalty that ranks every
infeasible design behind every feasible one (Deb, Comput. Methods Appl. Mech. Eng. 186 (2000)
311-338): the objective of a feasible design, else 1e30 times (1 + the summed relative violation).
A warning does not by itself make a design infeasible: the constraints say what must hold.
"""
from __future__ import annotations

import fnmatch
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..core.errors import ModelError
from .cases import COMPLETED, resolve
from .design import Design, column_values, overrides_of
from .spec import to_number

#: what an infeasible design scores (every feasible one scores less)
INFEASIBLE = 1e30


class Evaluation(NamedTuple):
    """One design evaluated: its generation, case, record, the score differential evolution saw,
    whether it met every constraint and ran to its end, and its objective (nan when infeasible)."""

    generation: int
    case: object
    record: dict
    score: float
    feasible: bool
    objective: float


@dataclass
class Optimum:
    """What an optimisation found: the best feasible design (None when none was), its objective,
    the evaluations in order, and the best feasible objective after each."""

    values: dict | None
    objective: float
    toml: str | None
    constraints: dict                  # key -> {"value", "min", "max", "margin"}
    evaluations: list = field(default_factory=list)   # Evaluation, in order
    history: list = field(default_factory=list)
    start: dict | None = None          # the design as the base file gives it: objective, feasible, constraints


def _matches(summary: dict, pattern: str) -> list:
    if pattern in summary:
        return [summary[pattern]]
    return [v for k, v in summary.items() if fnmatch.fnmatchcase(k, pattern)]


def _extreme(values, largest: bool):
    """One number from the matches of a key: each list by its extreme, then the extreme of all."""
    flat = []
    for v in values:
        flat += [x for x in (v if isinstance(v, list) else [v]) if isinstance(x, (int, float)) and math.isfinite(x)]
    if not flat:
        return None
    return max(flat) if largest else min(flat)


def judge(opt, record, units) -> tuple[float, bool, dict, float]:
    """(score, feasible, constraint values, objective) of one evaluated design."""
    summary = record.get("summary", {}) if record else {}
    ok = bool(record) and record.get("status") in COMPLETED
    obj = _extreme(_matches(summary, opt.objective), largest=opt.sign > 0)
    if obj is None:
        ok = False
    violation, cons = 0.0, {}
    for c in opt.constraints:
        unit = next((u for k, u in units.items() if fnmatch.fnmatchcase(k, c.key)), None)
        vals = _matches(summary, c.key)
        entry = {}
        for side, bound in (("max", c.max), ("min", c.min)):
            if bound is None:
                continue
            b = to_number(bound, unit or None)
            v = _extreme(vals, side == "max")
            if v is None:
                ok = False
                continue
            excess = (v - b) if side == "max" else (b - v)
            entry.update({"value": v, side: b, "margin": -excess if "margin" not in entry else min(entry["margin"], -excess)})
            if excess > 0:
                violation += excess / max(abs(b), 1e-12)
        cons[c.key] = entry
    if not ok or violation > 0:
        return INFEASIBLE * (1 + violation + (0 if ok else 1)), False, cons, math.nan
    return opt.sign * obj, True, cons, obj


def _check_keys(opt, records):
    """The objective and every constraint name summary keys that the designs' results have, and
    each constraint's bounds read in those keys' units (a typo would otherwise spend the whole
    budget on infeasible designs; a wrong unit fail inside scipy)."""
    import difflib

    done = [r for r in records if r.get("status") in COMPLETED]
    if not done:
        return
    keys = set().union(*(r.get("summary", {}).keys() for r in done))
    units = {}
    for r in done:
        units.update(r.get("units") or {})
    for name, pattern in [("optimise.objective", opt.objective)] + [(f"optimise.constraints[{i}].key", c.key)
                                                                     for i, c in enumerate(opt.constraints)]:
        if pattern not in keys and not any(fnmatch.fnmatchcase(k, pattern) for k in keys):
            close = difflib.get_close_matches(pattern, sorted(keys), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ModelError(f"no summary key {pattern!r} in the designs' results{hint}", field=name)
    for i, c in enumerate(opt.constraints):
        unit = next((u for k, u in units.items() if fnmatch.fnmatchcase(k, c.key)), None)
        for side in ("min", "max"):
            bound = getattr(c, side)
            if bound is not None:
                try:
                    to_number(bound, unit or None)
                except ModelError as exc:
                    raise ModelError(f"{exc} (the unit of {c.key!r} is {unit})", field=f"optimise.constraints[{i}].{side}") from None


def run_optimise(study, execute) -> Optimum:
    """Differential evolution over ``study``'s ranged parameters. ``execute(cases)`` runs the cases
    of one generation that its cache lacks (execute.run_optimisation's batch runner) and returns
    key -> record for all of them; ``execute(cases, probe=True)`` runs a design ahead of its
    generation (not counted as evaluated: the generation's call returns its record again)."""
    from scipy.optimize import differential_evolution

    spec = study.spec
    opt = spec.optimise
    params = spec.parameters
    labels = [p.label for p in params]
    d = len(params)
    evaluations, history = [], []
    best = {"score": math.inf, "case": None, "objective": math.nan, "cons": {}}
    units_seen: dict = {}
    generation = [0]
    stop = [None]
    checked = [False]

    def batch(_func, population):
        pop = np.atleast_2d(np.array(list(population), dtype=float))
        if stop[0] is not None:      # refused: scipy asks for one more generation before its callback stops it
            return [INFEASIBLE] * len(pop)
        cols = [column_values(p, study.units[p.label], pop[:, j]) for j, p in enumerate(params)]
        design = Design(labels, False, {}, [dict(zip(labels, row)) for row in zip(*cols)])
        cases = resolve(study, design, overrides_of)
        for i, c in enumerate(cases):
            c.index = len(evaluations) + i
        if generation[0] == 0:
            # The summary keys a design gives are known for certain only from a design's result:
            # they follow the model's names and the path its analysis takes (a run-up, the
            # rotational model, clutches, a planetary stage), and a catalogue of them written
            # beside the four analyses would be a second description that drifts from the code
            # that writes the summaries. So the first design of the first generation is evaluated
            # alone (check's data: milliseconds; a lean run-up: about a second; a full run: one
            # design's time) and the objective and the constraints are read against its keys and
            # units before the rest of the generation runs. It is a member of the generation: its
            # record is reused, nothing runs twice. If it did not finish, the keys are read after
            # the generation, as before.
            first = next((c for c in cases if c.toml is not None), None)
            if first is not None:
                probe = execute([first], probe=True)
                rec = probe.get(first.key)
                if rec is not None and rec.get("status") in COMPLETED:
                    try:
                        _check_keys(opt, [rec])
                    except ModelError as exc:     # scipy would wrap it: stop the optimisation, raise it then
                        stop[0] = exc
                        return [INFEASIBLE] * len(cases)
                    checked[0] = True
        records = execute(cases)
        scores = []
        for c in cases:
            rec = records.get(c.key) or {"status": "invalid" if c.toml is None else "missing", "message": c.message, "summary": {}}
            units_seen.update(rec.get("units") or {})
            score, feasible, cons, obj = judge(opt, rec, units_seen)
            evaluations.append(Evaluation(generation[0], c, rec, score, feasible, obj))
            if feasible and score < best["score"]:
                best.update(score=score, case=c, objective=obj, cons=cons)
            history.append(best["objective"])
            scores.append(score)
        if generation[0] == 0 and not checked[0]:
            try:
                _check_keys(opt, [e.record for e in evaluations[-len(cases):]])
            except Exception as exc:       # scipy would wrap it: stop at the generation's end, raise it then
                stop[0] = exc
        generation[0] += 1
        return scores

    popsize = max(opt.population, 1)
    per_gen = popsize * d
    maxiter = max(0, opt.budget // per_gen - 1)
    # integer parameters are rounded where the unit cube maps to values (design.column_values)
    differential_evolution(lambda x: 0.0, [(0.0, 1.0)] * d, popsize=popsize, maxiter=maxiter, seed=opt.seed,
                           workers=batch, updating="deferred", polish=False, init="latinhypercube", tol=1e-6,
                           callback=lambda *a, **k: stop[0] is not None)
    if stop[0] is not None:
        raise stop[0]
    start = _start(study, execute, opt, units_seen)
    if best["case"] is None:
        return Optimum(None, math.nan, None, {}, evaluations, history, start)
    return Optimum(dict(best["case"].values), best["objective"], best["case"].toml, best["cons"], evaluations, history,
                   start)


def _start(study, execute, opt, units) -> dict | None:
    """The design the optimisation started from, the base file with its overrides and no parameter changed
    (the round sprocket of an ovality study, the shipped tensioner): evaluated once, beside the designs
    (not one of them), so that what the optimum gains is said against it. None when it does not run."""
    cases = resolve(study, Design([p.label for p in study.spec.parameters], False, {}, [{}]), lambda _s, _c: {})
    case = cases[0]
    if case.toml is None:
        return None
    rec = execute([case], probe=True).get(case.key)
    if rec is None or rec.get("status") not in COMPLETED:
        return None
    _score, feasible, cons, obj = judge(opt, rec, units)
    return {"objective": obj, "feasible": feasible, "constraints": cons, "status": rec.get("status"),
            "toml": case.toml}


class SpeedRange(NamedTuple):
    """An objective read off a run-up, bin by bin, for the base file's design and the best one."""
    quantity: str            # what the rows hold, in words
    unit: str
    rpm: list
    base: list
    best: list


def speed_range(opt: Optimum, objective: str) -> SpeedRange | None:
    """For an objective that is a run-up's peak or a run-up table's entry (``runup.order_peaks.*`` or
    ``runup.span_tension_max.<span>``, ...): the base file's design and the best design run once more
    in full, and the objective's quantity read in each crank-speed bin of both, so that a report shows
    the gain through the speed range, not at its worst bin alone. None for any other objective or
    when either run fails."""
    from ..api import run
    from ..belt.dynamics.runup import ORDER_VARIABLES
    from ..core.errors import SolverError
    from ..core.model import loads

    parts = objective.split(".")
    if parts[0] != "runup" or opt.toml is None or not opt.start or not opt.start.get("toml"):
        return None
    if parts[1] == "order_peaks" and (len(parts) != 6 or parts[2] not in ORDER_VARIABLES or parts[5] != "amplitude"):
        return None
    if parts[1] != "order_peaks" and len(parts) != 3:
        return None
    rows = []
    for toml in (opt.start["toml"], opt.toml):
        try:
            res = run(loads(toml, source="the optimisation's design"))
        except (ModelError, SolverError):
            return None
        ru = res.summary.get("runup") or {}
        if parts[1] == "order_peaks":
            var, dim = ORDER_VARIABLES[parts[2]]
            try:
                da = res.ds[var].sel({dim: parts[3], "order": float(parts[4])})
            except (KeyError, ValueError):       # no such table, name or order in this run
                return None
            vals, unit = [float(v) for v in da.values], str(res.ds[var].attrs.get("units", ""))
            what = f"{parts[2].replace('_', ' ')} {parts[3]}, order {parts[4]} amplitude"
        else:
            table = ru.get(parts[1])
            if not isinstance(table, dict) or not isinstance(table.get(parts[2]), list):
                return None
            vals, unit = [float(v) for v in table[parts[2]]], str(res.units.get(objective, ""))
            what = f"{parts[1].replace('_', ' ')} {parts[2]}"
        rows.append((list(ru.get("speed_rpm", [])), vals))
    (rpm0, base), (rpm1, best) = rows
    if rpm0 != rpm1 or len(base) != len(rpm0):
        return None
    return SpeedRange(what, unit, rpm0, base, best)


def plot_speed_range(sr: SpeedRange, path: Path) -> Path:
    """The objective's quantity per crank-speed bin, the base file's design against the best."""
    from ..core.plotting import figure, savefig

    fig, axes = figure()
    ax = axes[0, 0]
    ax.plot(sr.rpm, sr.base, "o-", ms=3, label="the base file's design")
    ax.plot(sr.rpm, sr.best, "s-", ms=3, label="the best design")
    ax.set_xlabel("crank speed (rpm)")
    ax.set_ylabel(sr.unit if sr.unit not in ("", "1") else "value")
    ax.set_title(f"through the speed range: {sr.quantity}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, frameon=False)
    return savefig(fig, path)


#: an optimum closer than this share of its range (in the range's own scale) to a bound sits on it
ON_BOUND = 0.02


def on_bounds(study, values: dict) -> list[dict]:
    """The ranged parameters whose optimum value sits on a bound of its range: the optimum may lie
    outside the design space (``[{"name", "value", "bound", "side"}]``)."""
    from .spec import to_number

    hits = []
    for p in study.spec.parameters:
        v = values.get(p.label) if values else None
        if p.range is None or not isinstance(v, (int, float)):
            continue
        unit = study.units.get(p.label)
        lo, hi = (to_number(b, unit) for b in p.range)
        if p.scale == "log" and lo > 0 and hi > 0 and v > 0:
            u = (math.log(v) - math.log(lo)) / (math.log(hi) - math.log(lo))
        else:
            u = (v - lo) / (hi - lo) if hi != lo else 0.5
        if p.integer:      # an integer's bound is a step away at most
            at_lo, at_hi = round(v) <= math.ceil(lo), round(v) >= math.floor(hi)
        else:
            at_lo, at_hi = u <= ON_BOUND, u >= 1 - ON_BOUND
        if at_lo or at_hi:
            hits.append({"name": p.label, "value": float(v), "bound": float(lo if at_lo else hi),
                         "side": "lower" if at_lo else "upper", "unit": unit or "", "share": ON_BOUND})
    return hits


def plot_convergence(opt: Optimum, path: Path, objective: str, sense: str, unit: str = "") -> Path:
    """The best feasible objective against the designs evaluated, each feasible design's dotted."""
    from ..core.plotting import figure, savefig

    fig, axes = figure()
    ax = axes[0, 0]
    n = np.arange(1, len(opt.evaluations) + 1)
    ax.plot(n, [e.objective for e in opt.evaluations], ".", ms=3, color="0.6", label="feasible designs")
    ax.plot(n, opt.history, lw=1.6, label="best feasible so far")
    ax.set_xlabel("designs evaluated")
    ax.set_ylabel(objective + (f" ({unit})" if unit else ""))
    ax.set_title(f"optimisation ({sense}): objective of the best feasible design")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, frameon=False)
    return savefig(fig, path)
