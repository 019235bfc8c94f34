"""What a run may cost, known before it starts: integration steps and result bytes.

A model that asks for more than these limits is refused when it is read (or, for the belt's step,
when the drive is assembled, before the solve), with one line giving the estimate, the limit and
how to change it. The limits are set for a workstation; a batch machine raises them through the
environment (``DRIVEDYN_MAX_STEPS``, ``DRIVEDYN_MAX_BYTES``, ``DRIVEDYN_MAX_BALANCES``,
``DRIVEDYN_MAX_EVALUATIONS``; studies:
``DRIVEDYN_MAX_CASES``). docs/limits.md lists them.
"""
from __future__ import annotations

import os

#: most integration steps of one run: 1e9 steps of the belt's semi-implicit scheme (3-10 us each
#: on the examples) are one to three hours; 1e-12 s steps for a second would be days
MAX_STEPS = 1e9
#: most bytes of arrays a run may hold (its samples and frames, as estimated from the model):
#: 2 GB, or half of the machine's memory if that is less
MAX_BYTES = 2e9
#: most steady balances of duty rows one check or run solves (a supplier report's running arm, by
#: creep theory: 40-70 ms each on examples/fead-ag0868.toml, so 2000 are one to two minutes)
MAX_BALANCES = 2000
#: most segment evaluations (steps x stages x segments) of one run of the explicit rkf45 scheme: one
#: evaluation of the chain costs about 0.1 us a segment (18 us for 150 segments of
#: examples/belt-5pk.toml, measured on a loaded two-core machine), so 1e9 are two to four minutes.
#: The steps limit alone let 3.8e6 steps of six stages at 150 segments through: ten minutes for 0.5 ms
MAX_EVALUATIONS = 1e9
#: seconds one segment evaluation of rkf45 takes, at least (its refusal's time): the count is from the
#: stability bound, and the run's own step settles below it (7.5e-11 s against 1.3e-10 s there)
EVALUATION_SECONDS = 0.1e-6


def _env(name: str, default: float) -> float:
    try:
        v = float(os.environ.get(name, default))
    except ValueError:
        return default
    return v if v > 0 else default


def max_steps() -> float:
    return _env("DRIVEDYN_MAX_STEPS", MAX_STEPS)


def max_bytes() -> float:
    limit = _env("DRIVEDYN_MAX_BYTES", MAX_BYTES)
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
        if "DRIVEDYN_MAX_BYTES" not in os.environ and memory > 0:
            limit = min(limit, 0.5 * memory)
    except (ValueError, OSError, AttributeError):
        pass
    return limit


def steps_problem(steps: float, what: str, fix: str) -> str | None:
    """None if ``steps`` fits the limit, else the one-line refusal."""
    limit = max_steps()
    if steps <= limit * (1 + 1e-9):       # a run at exactly the limit (its steps from a float division)
        return None
    digits = 3
    while f"{steps:.{digits}g}" == f"{limit:.{digits}g}" and digits < 12:     # never two equal numbers
        digits += 1
    return (f"{what}: {steps:.{digits}g} integration steps, more than the {limit:.{digits}g} a run may take ({fix}, "
            "or set DRIVEDYN_MAX_STEPS)")


def bytes_problem(nbytes: float, what: str, fix: str) -> str | None:
    """None if ``nbytes`` fits the limit, else the one-line refusal."""
    limit = max_bytes()
    if nbytes <= limit:
        return None
    return (f"{what}: the results would take about {nbytes / 1e9:.3g} GB, more than the {limit / 1e9:.3g} GB "
            f"allowed ({fix}, or set DRIVEDYN_MAX_BYTES)")


def max_balances() -> float:
    return _env("DRIVEDYN_MAX_BALANCES", MAX_BALANCES)


def balances_problem(count: float, what: str, fix: str) -> str | None:
    """None if ``count`` steady balances fit the limit, else the one-line refusal."""
    limit = max_balances()
    if count <= limit:
        return None
    return (f"{what}: {count:.6g} steady balances of duty rows, more than the {limit:.6g} a check or run may solve "
            f"(40-70 ms each; {fix}, or set DRIVEDYN_MAX_BALANCES)")


def max_evaluations() -> float:
    return _env("DRIVEDYN_MAX_EVALUATIONS", MAX_EVALUATIONS)


def evaluations_problem(count: float, what: str, fix: str) -> str | None:
    """None if ``count`` segment evaluations of an explicit run fit the limit, else the one-line refusal."""
    limit = max_evaluations()
    if count <= limit:
        return None
    minutes = count * EVALUATION_SECONDS / 60
    return (f"{what}: {count:.2g} segment evaluations (at least {minutes:.2g} minutes), more than the {limit:.2g} "
            f"an explicit run may take ({fix}, or set DRIVEDYN_MAX_EVALUATIONS)")
