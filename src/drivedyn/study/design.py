"""Designs of experiments: the list of cases a study runs.

A grid is the Cartesian product of every parameter's values (C order: the last parameter varies
fastest), and the study Dataset gets one dimension per parameter. Sampled designs (Latin
hypercube, Sobol, Monte Carlo) draw ``samples`` points in the unit hypercube with
``scipy.stats.qmc`` or numpy's generator, seeded, and map each column onto its parameter (uniform
or log-uniform on a range, a normal distribution by its inverse CDF, a pick from a list); the
Dataset then has a ``case`` dimension with the parameters as coordinates along it.
"""
from __future__ import annotations

import itertools
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..core.errors import DrivedynWarning, ModelError
from .spec import Parameter, to_number


@dataclass
class Design:
    """The cases of a study.

    Attributes
    ----------
    labels : list of str
        Parameter names (Dataset dimension or coordinate names), in file order.
    grid : bool
        True for a full grid (one dimension per parameter), False for a ``case`` dimension.
    axes : dict
        Grid only: label -> the list of values along that dimension.
    cases : list of dict
        One dict per case: label -> value (SI float, or the string/bool given).
    """

    labels: list[str]
    grid: bool
    axes: dict = field(default_factory=dict)
    cases: list[dict] = field(default_factory=list)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(self.axes[k]) for k in self.labels) if self.grid else (len(self.cases),)

    @property
    def dims(self) -> tuple[str, ...]:
        return tuple(self.labels) if self.grid else ("case",)


def _finish(p: Parameter, x):
    if p.integer and isinstance(x, float):
        return float(round(x))
    return x


def axis_values(p: Parameter, unit: str) -> list:
    """The values of ``p`` along a grid dimension."""
    if p.values is not None:
        vals = [_finish(p, to_number(v, unit)) for v in p.values]
    else:
        lo, hi = (to_number(v, unit) for v in p.range)
        n = p.num or 1
        pts = np.geomspace(lo, hi, n) if p.scale == "log" else np.linspace(lo, hi, n)
        vals = [_finish(p, float(x)) for x in pts]
    if len(set(map(repr, vals))) != len(vals):
        # a duplicated coordinate would make .sel() ambiguous; usually integer rounding of a range
        raise ModelError(f"parameters: {p.label!r} has repeated values {vals} (fewer points, or integer = false)")
    return vals


def unit_cube(method: str, n: int, d: int, seed: int) -> np.ndarray:
    """``n`` points in [0, 1)^d drawn by ``method`` (lhs, sobol, montecarlo), reproducible by ``seed``."""
    rng = np.random.default_rng(seed)
    if method == "montecarlo":
        return rng.random((n, d))
    from scipy.stats import qmc

    if method == "lhs":
        return qmc.LatinHypercube(d, rng=rng).random(n)
    if method == "sobol":
        if n & (n - 1):
            warnings.warn(f"a Sobol design keeps its balance properties only for a power of 2 samples (got {n})",
                          DrivedynWarning, stacklevel=3)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # scipy's own balance warning repeats the one above
            return qmc.Sobol(d, scramble=True, rng=rng).random(n)
    raise ModelError(f"unknown sampler {method!r}")


def column_values(p: Parameter, unit: str, u: np.ndarray) -> list:
    """Map unit-interval samples ``u`` onto the values of ``p``."""
    if p.values is not None:
        vals = [to_number(v, unit) for v in p.values]
        idx = np.minimum((u * len(vals)).astype(int), len(vals) - 1)
        return [_finish(p, vals[i]) for i in idx]
    if p.mean is not None:
        from scipy.stats import norm

        mu, sd = to_number(p.mean, unit), to_number(p.std, unit)
        # clip so that a Monte Carlo draw of exactly 0 does not map to -inf
        x = mu + sd * norm.ppf(np.clip(u, 1e-12, 1 - 1e-12))
        return [_finish(p, float(v)) for v in x]
    lo, hi = (to_number(v, unit) for v in p.range)
    if p.scale == "log":
        x = np.exp(math.log(lo) + u * (math.log(hi) - math.log(lo)))
    else:
        x = lo + u * (hi - lo)
    return [_finish(p, float(v)) for v in x]


def make_design(study) -> Design:
    """The design (all cases) of a loaded :class:`~drivedyn.study.spec.Study`."""
    spec = study.spec
    params = spec.parameters
    labels = [p.label for p in params]
    if spec.sampler.method == "grid":
        axes = {p.label: axis_values(p, study.units[p.label]) for p in params}
        cases = [dict(zip(labels, combo)) for combo in itertools.product(*(axes[k] for k in labels))]
        return Design(labels, True, axes, cases)
    n = spec.sampler.samples
    u = unit_cube(spec.sampler.method, n, len(params), spec.sampler.seed)
    cols = [column_values(p, study.units[p.label], u[:, j]) for j, p in enumerate(params)]
    cases = [dict(zip(labels, row)) for row in zip(*cols)]
    return Design(labels, False, {}, cases)


def overrides_of(study, case: dict) -> dict:
    """Model path -> value for one case (linked paths get the value times their factor)."""
    out = {}
    for p in study.spec.parameters:
        v = case[p.label]
        for k, path in enumerate(p.paths):
            f = p.factors[k] if p.factors is not None else 1.0
            if f != 1.0:
                if not isinstance(v, float):
                    raise ModelError(f"parameters: {p.label!r}: factors need numeric values, got {v!r}")
                x = v * f
            else:
                x = v
            # whole numbers stay ints so integer fields (segments, counts) validate
            if p.integer and isinstance(x, float):
                x = int(round(x))
            out[path] = x
    return out
