"""Design criteria and the verdict: is the drive acceptable, and why.

Every analysis may declare a ``[criteria]`` section in its model file (its fields and defaults are
in the analysis's ``criteria.py``; docs/criteria.md states where each default comes from). After a
run, :func:`judge` evaluates them on the Result and writes into its summary

    summary["verdict"]             "pass", "fail" or "not judged"
    summary["criteria"][name]      {"value", "limit", "unit", "pass", "text"}

"pass" means every criterion that could be evaluated holds; "fail" that at least one does not;
"not judged" that the run failed (partial results) or no criterion applies. A criterion whose
limit is not given (and has no default) is not evaluated. The status of the run (success /
warning / failed, the diagnostics) is separate: it says whether the numbers can be trusted, the
verdict what they mean for the design.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

PASS, FAIL, NOT_JUDGED = "pass", "fail", "not judged"


@dataclass
class Criterion:
    """One criterion evaluated: ``value`` against ``limit`` (``kind`` "max": value <= limit;
    "min": value >= limit), with the object it was found on and a short sentence."""

    name: str
    value: float
    limit: float
    unit: str
    kind: str               # "max" or "min"
    text: str = ""
    where: str = ""         # the pulley, span, bin ... where the value was found
    details: list = field(default_factory=list)   # e.g. the crossings listed

    @property
    def passed(self) -> bool:
        if self.value is None or (isinstance(self.value, float) and math.isnan(self.value)):
            return False
        return self.value <= self.limit if self.kind == "max" else self.value >= self.limit

    def to_dict(self) -> dict:
        out = {"value": _num(self.value), "limit": _num(self.limit), "unit": self.unit, "pass": self.passed,
               "kind": self.kind, "text": self.text}
        if self.where:
            out["where"] = self.where
        if self.details:
            out["details"] = self.details
        return out


def _num(v):
    return None if v is None else float(v)


def verdict_of(criteria: list[Criterion], status: str) -> str:
    if status == "failed" or not criteria:
        return NOT_JUDGED
    return PASS if all(c.passed for c in criteria) else FAIL


def judge(model, result):
    """Evaluate the model's criteria on ``result`` and write ``verdict`` and ``criteria`` first
    in its summary (and their units). Returns the result. Never raises for a criterion that
    cannot be evaluated: it is left out and said so under ``criteria_skipped``."""
    from .analyses import analysis

    found, skipped = [], {}
    if result.status != "failed":
        fn = analysis(result.kind).criteria_fn()
        if fn is not None:
            found, skipped = fn(model, result)
    verdict = verdict_of(found, result.status)
    head = {"verdict": verdict, "criteria": {c.name: c.to_dict() for c in found}}
    if skipped:
        head["criteria_skipped"] = skipped
    rest = {k: v for k, v in result.summary.items() if k not in ("verdict", "criteria", "criteria_skipped")}
    result.summary.clear()
    result.summary.update(head)
    result.summary.update(rest)
    for c in found:
        if c.unit:
            result.units[f"criteria.{c.name}.value"] = c.unit
            result.units[f"criteria.{c.name}.limit"] = c.unit
    return result


def failed(summary: dict) -> list[str]:
    """Names of the failed criteria in a summary."""
    return [n for n, c in (summary.get("criteria") or {}).items() if not c.get("pass")]


# -- how a criterion reads -------------------------------------------------------------------

#: display of an SI unit in the verdict table: (unit shown, factor from SI)
SHOW = {"1": ("%", 100.0), "rad": ("deg", 180 / math.pi), "rad/s": ("rpm", 30 / math.pi)}


def shown(value, unit: str, percent: bool = False):
    """(text, unit) of a criterion value as people read it: fractions as %, angles in degrees."""
    if value is None:
        return "-", ""
    if unit == "1" and not percent:
        return f"{value:.3g}", ""
    u, f = SHOW.get(unit, (unit, 1.0))
    v = value * f + 0.0
    if 1e4 <= abs(v) < 1e9:            # a life in hours, a load in N: whole numbers, no exponent
        return f"{v:.0f}", u
    return (f"{v:.4g}" if abs(v) >= 1e-3 or v == 0 else f"{v:.3g}"), u


def rows(summary: dict) -> list[dict]:
    """The verdict table: one row per criterion (name, value, limit, unit, pass, where, text)."""
    out = []
    for name, c in (summary.get("criteria") or {}).items():
        pct = c.get("unit") == "1" and c.get("percent", name in PERCENT)
        v, u = shown(c.get("value"), c.get("unit", ""), pct)
        lim, _ = shown(c.get("limit"), c.get("unit", ""), pct)
        rel = "<=" if c.get("kind") == "max" else ">="
        out.append({"name": name, "value": v, "limit": f"{rel} {lim}", "unit": u,
                    "pass": "pass" if c.get("pass") else "FAIL", "ok": bool(c.get("pass")),
                    "where": c.get("where", ""), "text": c.get("text", ""),
                    "details": c.get("details", [])})
    return out


#: fraction-valued criteria shown in % (slip); other "1" values (margins, ratios) as numbers
PERCENT = {"slip_mean", "slip_runup", "stop_clearance", "duty_stop_clearance"}
