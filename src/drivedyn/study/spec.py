"""The study file (TOML): what to vary in which base model, how to sample it, what to keep.

A study file is pure data, validated like a model file (unknown keys are errors, one line naming
the key). Parameter paths are checked against the base model *before* anything runs, so a typo
in ``belt.pretension`` costs a second, not a cluster start::

    base = "belt-5pk.toml"                   # relative to this file
    [overrides]                              # fixed changes to the base model, every case
    "simulation.duration" = "0.6 s"
    [[parameters]]
    path = "belt.pretension"
    range = ["300 N", "800 N"]
    num = 4
    [sampler]
    method = "grid"
"""
from __future__ import annotations

import difflib
import math
import re
from pathlib import Path
from typing import Any, Literal, Optional, Union

from pydantic import ValidationError, field_validator, model_validator

from ..core.errors import ModelError
from ..core.model import Spec, field_unit, format_validation_error, from_dict, quantity, read_toml, schema_step, set_path, to_dict
from ..core.model import unwrap as _unwrap

#: most cases a study may have (a grid's product of points, or samples): 100 000 cases of the
#: fastest kind (check mode, ~5 ms each) take minutes; more is a typo or a job for several studies
MAX_CASES = 100_000
CASES_VARIABLE = "DRIVEDYN_MAX_CASES"


def max_cases() -> float:
    """The case limit: :data:`MAX_CASES`, or the environment's ``DRIVEDYN_MAX_CASES`` read as the other
    limits are (limits.py: a value that is not a positive number is ignored; "inf" lifts the limit;
    it was int(inf), an OverflowError traceback under every study command)."""
    from ..core.limits import _env

    v = _env(CASES_VARIABLE, MAX_CASES)
    return float(math.floor(v)) if math.isfinite(v) and v >= 1 else (v if v > 1 else 1.0)


def check_cases(n, what: str, fix: str = "") -> None:
    """Refuse ``n`` cases past :func:`max_cases` in one line (``what``: the count named, ``{n}`` in it
    for the number; ``fix``: what to change besides the limit)."""
    limit = max_cases()
    if n > limit:
        raise ValueError(f"{what.format(n=f'{n:.4g}')}, more than the {limit:.6g} cases a study may have "
                         f"({fix + ', or ' if fix else ''}set {CASES_VARIABLE} to allow more)")


#: accepted sampler names -> canonical name (the aliases are what people type)
SAMPLERS = {
    "grid": "grid",
    "lhs": "lhs", "latin-hypercube": "lhs", "latin_hypercube": "lhs",
    "sobol": "sobol",
    "montecarlo": "montecarlo", "monte-carlo": "montecarlo", "random": "montecarlo",
}


def _finite(v, what: str):
    """A bound or value as given (a number, or a string with a unit): refused when its number is
    not finite (NaN would mark every design feasible, an infinite range samples nothing)."""
    try:
        x = float(v) if not isinstance(v, str) else float(v.strip().split()[0])
    except (TypeError, ValueError, IndexError):
        return v                                 # not a plain number: the units check reads it
    if not math.isfinite(x):
        raise ValueError(f"{what} must be a finite number, got {v!r}")
    return v


class Parameter(Spec):
    """One swept parameter.

    Exactly one of ``values`` (a list), ``range`` (``[low, high]``) or ``mean`` + ``std``
    (normal distribution, sampled designs only) describes its values. ``path`` may list several
    model paths that move together, each multiplied by its entry in ``factors``.
    """

    path: Union[str, list[str]]
    """Dotted path of the model field varied ("belt.pretension", "pulleys.alternator.inertia": list items by name or
    index), or a list of paths that move together."""
    name: Optional[str] = None
    """Name of the parameter in the study's results; needed when path lists several paths; none: the path."""
    values: Optional[list[Any]] = None
    """The values, as a list (numbers or strings with units)."""
    range: Optional[tuple[Any, Any]] = None
    """The range [low, high] (numbers or strings with units): num points of a grid, or the bounds of a sampled design
    or of an optimisation."""
    num: Optional[int] = None
    """Number of grid points over range."""
    scale: Literal["linear", "log"] = "linear"
    """Spacing of the points over range: "linear" or "log"."""
    mean: Optional[Any] = None
    """Mean of a normally distributed parameter (with std; sampled designs only)."""
    std: Optional[Any] = None
    """Standard deviation of a normally distributed parameter (with mean)."""
    integer: bool = False
    """Round the values to integers (segment counts, tooth counts)."""
    factors: Optional[list[float]] = None
    """One factor per path: each path gets the value times its factor."""
    unit: Optional[str] = None
    """Unit of the values where the model field declares none (table entries, plain floats): strings with units are
    read in it and the study's coordinate is labelled with it (the field itself takes SI values)."""

    @field_validator("path")
    @classmethod
    def _paths(cls, v):
        paths = [v] if isinstance(v, str) else list(v)
        if not paths or any(not p or not isinstance(p, str) for p in paths):
            raise ValueError("must be a dotted path such as 'belt.pretension' (or a list of them)")
        return v

    @field_validator("num")
    @classmethod
    def _num(cls, v):
        if v is not None and v < 1:
            raise ValueError(f"must be >= 1, got {v}")
        if v is not None:
            check_cases(v, "{n} points", "fewer points")
        return v

    @model_validator(mode="after")
    def _one_description(self):
        given = [k for k in ("values", "range", "mean") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(f"parameter {self.label!r}: give exactly one of values, range or mean+std"
                             + (f" (got {', '.join(given)})" if given else ""))
        if (self.mean is None) != (self.std is None):
            raise ValueError(f"parameter {self.label!r}: a normal distribution needs both mean and std")
        if self.values is not None and len(self.values) == 0:
            raise ValueError(f"parameter {self.label!r}: values is empty")
        if self.num is not None and self.range is None:
            raise ValueError(f"parameter {self.label!r}: num goes with range")
        for k, v in enumerate(self.range or ()):
            _finite(v, f"parameter {self.label!r}: range[{k}]")
        if self.integer and self.range is not None and all(isinstance(v, (int, float)) for v in self.range):
            lo, hi = sorted(self.range)
            if math.ceil(lo) > math.floor(hi):
                raise ValueError(f"parameter {self.label!r}: integer = true, but range [{self.range[0]}, "
                                 f"{self.range[1]}] holds no integer")
        for k in ("mean", "std"):
            if getattr(self, k) is not None:
                _finite(getattr(self, k), f"parameter {self.label!r}: {k}")
        if isinstance(self.path, list) and len(self.path) > 1 and not self.name:
            raise ValueError("a parameter that sets several paths needs a name")
        if self.factors is not None and len(self.factors) != len(self.paths):
            raise ValueError(f"parameter {self.label!r}: factors needs one number per path ({len(self.paths)})")
        return self

    @property
    def paths(self) -> list[str]:
        return [self.path] if isinstance(self.path, str) else list(self.path)

    @property
    def label(self) -> str:
        """The dimension / coordinate name in the study Dataset (a '/' in it, which netCDF reads as
        a group separator, written as '_'; a very long one shortened with a stable hash)."""
        from ..core.outputs import nc_name

        return nc_name(self.name or self.paths[0])


class Sampler(Spec):
    """How cases are drawn: a full ``grid`` or ``samples`` points of a sampled design."""

    method: str = "grid"
    """"grid" (every combination of the parameters' values), or a sampled design: "lhs" (Latin hypercube), "sobol",
    "montecarlo"."""
    samples: Optional[int] = None
    """Number of cases of a sampled design (not with grid)."""
    seed: int = 0
    """Seed of the random numbers of a sampled design (the same seed gives the same cases)."""

    @field_validator("method")
    @classmethod
    def _method(cls, v):
        key = str(v).strip().lower()
        if key not in SAMPLERS:
            close = difflib.get_close_matches(key, SAMPLERS, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"unknown sampler {v!r}{hint}; one of grid, lhs, sobol, montecarlo")
        return SAMPLERS[key]

    @model_validator(mode="after")
    def _samples(self):
        if self.method == "grid" and self.samples is not None:
            raise ValueError("sampler.samples does not apply to a grid (its size is the product of the parameters' num)")
        if self.method != "grid" and (self.samples is None or self.samples < 1):
            raise ValueError(f"the {self.method} sampler needs samples = N (>= 1)")
        if self.samples is not None:
            check_cases(self.samples, "samples: {n} cases", "fewer samples")
        return self


class Outputs(Spec):
    """What to keep of each case: summary keys (glob patterns) and whole Dataset variables."""

    summary: list[str] = ["*"]
    """Summary keys kept from each case, as glob patterns ("*": all)."""
    series: list[str] = []
    """Whole variables of each case's Dataset kept (time series, by name)."""


class Plots(Spec):
    """Which summary keys to plot against the parameters (default: the listed outputs)."""

    keys: Optional[list[str]] = None
    """Summary keys plotted against the parameters; none: the listed outputs."""
    enabled: bool = True
    """Draw the study's plots."""


class Constraint(Spec):
    """A bound on a summary quantity of every design: ``key`` (a summary key; ``*`` matches any part,
    every match must hold; a list such as a run-up's per-bin values counts by its extreme),
    ``min`` and / or ``max`` (with units, like parameter values)."""

    key: str
    """Summary key bounded ("*" matches any part; every match must hold; a list counts by its extreme)."""
    min: Optional[Any] = None
    """Lower bound (a number or a string with a unit); none: no lower bound."""
    max: Optional[Any] = None
    """Upper bound (a number or a string with a unit); none: no upper bound."""

    @model_validator(mode="after")
    def _bound(self):
        if self.min is None and self.max is None:
            raise ValueError(f"constraint {self.key!r}: give min or max (or both)")
        for k in ("min", "max"):
            if getattr(self, k) is not None:
                _finite(getattr(self, k), f"constraint {self.key!r}: {k}")
        return self


class Optimise(Spec):
    """Design by optimisation (``mode = "optimise"``): the ranged parameters are the design
    variables; ``objective`` a summary key (a list counts by its largest value when minimised, its
    smallest when maximised) to minimise or maximise; ``constraints`` bounds on summary keys;
    ``evaluate`` how a design is judged ("run" simulates it, "check" uses check's data); ``budget``
    the designs evaluated at most; differential evolution (Storn & Price, J. Global Optim. 11
    (1997) 341-359, scipy.optimize), each generation one batch of cases on the cluster."""

    objective: str
    """Summary key to minimise or maximise (a list counts by its largest value when minimised, its smallest when
    maximised)."""
    sense: Literal["minimise", "maximise"] = "minimise"
    """"minimise" or "maximise" ("minimize", "maximize" read as these)."""
    constraints: list[Constraint] = []
    """Bounds on summary keys that every accepted design must meet."""
    evaluate: Literal["run", "check"] = "run"
    """How a design is judged: "run" simulates it, "check" uses check's data (milliseconds per design)."""
    budget: int = 200
    """Designs evaluated at most."""
    population: int = 6
    """Designs per generation, per design variable (scipy's popsize of differential evolution; Storn & Price 1997)."""
    seed: int = 0
    """Seed of the optimiser's random numbers."""

    @field_validator("sense", mode="before")
    @classmethod
    def _spelling(cls, v):
        # a list or a table is left to the Literal's one line (a dict lookup of it was a TypeError)
        return {"minimize": "minimise", "maximize": "maximise"}.get(v, v) if isinstance(v, str) else v

    @property
    def sign(self) -> float:
        """+1 to minimise, -1 to maximise: the score differential evolution minimises is sign x objective."""
        return 1.0 if self.sense == "minimise" else -1.0

    @field_validator("budget", "population")
    @classmethod
    def _positive(cls, v):
        if v < 1:
            raise ValueError(f"must be >= 1, got {v}")
        check_cases(v, "{n} designs")
        return v

    @field_validator("seed")
    @classmethod
    def _seed(cls, v):
        # numpy's generators take seeds in [0, 2^32)
        if not 0 <= v < 2 ** 32:
            raise ValueError(f"must lie in [0, 2^32), got {v}")
        return v


class StudySpec(Spec):
    """The validated content of a study file."""

    kind: Literal["study"] = "study"
    """The kind of file: "study"."""
    schema_version: Literal[1] = 1
    """Version of the study-file format (1)."""
    name: str = ""
    """A name for the study; empty: the study file's name."""
    description: str = ""
    """Free text saying what the study is for (not used by the computation)."""
    base: Optional[str] = None
    """The base model file, relative to this file (give this or [model])."""
    model: Optional[dict[str, Any]] = None
    """The base model inline, as a table (give this or base)."""
    out: Optional[str] = None
    """Output folder, relative to the working folder; none: the study file's name."""
    overrides: dict[str, Any] = {}
    """Fixed changes to the base model in every case, by dotted path."""
    parameters: list[Parameter]
    """The parameters varied."""
    sampler: Sampler = Sampler()
    """How cases are drawn from the parameters."""
    outputs: Outputs = Outputs()
    """What is kept of each case."""
    plots: Plots = Plots()
    """Which summary keys are plotted."""
    case_timeout: Optional[quantity("s", gt=0)] = None
    """Wall-time limit per case, checked at the case's progress reports (belt: every 1 % of the simulated time); a
    case that exceeds it ends as "failed" and keeps what it computed; none: no limit."""
    mode: Literal["run", "check", "optimise"] = "run"
    """"run" simulates each case; "check" evaluates what check knows (belt drives: the creep-theory steady state, slip
    margins, modes) in milliseconds per case; "optimise": design by optimisation over the ranged parameters
    ([optimise]); "optimize" reads as "optimise"."""
    optimise: Optional[Optimise] = None
    """The optimisation: objective, constraints, budget (mode = "optimise")."""

    @field_validator("mode", mode="before")
    @classmethod
    def _spelling(cls, v):
        return "optimise" if v == "optimize" else v

    @property
    def eval_mode(self) -> str:
        """How one case is evaluated: "run" or "check" (an optimisation's ``evaluate``)."""
        return self.optimise.evaluate if self.mode == "optimise" else self.mode

    @model_validator(mode="after")
    def _consistent(self):
        if (self.base is None) == (self.model is None):
            raise ValueError("give exactly one of base (a model file) or [model] (the base model inline)")
        if not self.parameters:
            raise ValueError("parameters: a study needs at least one parameter")
        if self.mode == "optimise":
            if self.optimise is None:
                raise ValueError("mode = \"optimise\" needs an [optimise] table (objective, constraints)")
            fixed = [p.label for p in self.parameters if p.range is None]
            if fixed:
                raise ValueError(f"parameters {fixed}: an optimisation varies parameters over a range = [low, high]")
            # differential evolution's first generation is max(5, population x variables) designs
            # (scipy.optimize.differential_evolution): a smaller budget would be overrun by it
            first = max(5, self.optimise.population * len(self.parameters))
            if self.optimise.budget < first:
                raise ValueError(f"optimise.budget {self.optimise.budget} is less than one generation, {first} designs "
                                 f"(population {self.optimise.population} x {len(self.parameters)} variables, at least 5): "
                                 f"a budget >= {first} or a smaller population")
        elif self.optimise is not None:
            raise ValueError("[optimise] goes with mode = \"optimise\"")
        if self.mode == "check" and self.outputs.series:
            raise ValueError("outputs.series: a study with mode = \"check\" has no time series (summary keys only)")
        labels = [p.label for p in self.parameters]
        dup = sorted({x for x in labels if labels.count(x) > 1})
        if dup:
            raise ValueError(f"parameters: duplicate name(s) {dup}")
        if self.sampler.method == "grid" and self.mode != "optimise":   # an optimisation draws its designs
            for k, p in enumerate(self.parameters):
                if p.mean is not None:
                    raise ValueError(f"parameters[{k}]: a normal distribution (mean/std) needs a sampled design, not a grid")
                if p.range is not None and p.num is None:
                    raise ValueError(f"parameters[{k}]: a range on a grid needs num (number of points)")
            # the grid's size before anything is built: 1e6 cases would be minutes of validation
            # and gigabytes of case records before the first one runs
            check_cases(math.prod(len(p.values) if p.values is not None else p.num for p in self.parameters),
                        "parameters: the grid has {n} cases", "fewer points, a sampled design")
        return self

    @field_validator("out")
    @classmethod
    def _out(cls, v):
        # a study file names a folder under the working folder; anywhere else takes the command
        # line's -o (a study file from someone else must not choose where files are written)
        if v is not None:
            p = Path(v)
            if not v.strip() or p.is_absolute() or ".." in p.parts or v.startswith("~"):
                raise ValueError(f"must be a folder under the working folder, got {v!r} (an absolute path or '..' "
                                 "is given on the command line: drivedyn study FILE -o FOLDER)")
        return v


class Study:
    """A loaded study: the spec, its text, the base model and each parameter's SI unit.

    Attributes
    ----------
    spec : StudySpec
        The validated study file.
    text : str
        The study file as written (kept in the results' attrs).
    path : pathlib.Path or None
        Where the study file is (None when built from a dict).
    base_path : pathlib.Path
        The base model file (the study file itself for an inline ``[model]``).
    base : pydantic model
        The base model with the study's ``overrides`` applied.
    units : dict
        Parameter label -> SI unit of its values ("" when unknown or dimensionless).
    shown : dict
        Parameter label -> (unit, value per SI value) of the unit the study file writes its values
        in, where that is not SI ("1000 rpm": ("rpm", 9.549)): how the report and plots show it.
    """

    def __init__(self, spec: StudySpec, text: str, path: Path | None, base_path: Path, base, units: dict,
                 shown: dict | None = None):
        self.spec, self.text, self.path, self.base_path, self.base, self.units = spec, text, path, base_path, base, units
        self.shown = shown or {}

    @property
    def name(self) -> str:
        return self.spec.name or (self.path.stem if self.path else "study")

    def default_out(self) -> Path:
        """Output folder: ``out`` of the study file, else the study file's stem (both relative to
        cwd; ``out`` is validated to stay under it)."""
        from ..core.outputs import file_stem

        if self.spec.out:
            return Path(self.spec.out)
        return Path(file_stem(self.path.stem) if self.path else "study")


def load_study(path) -> Study:
    """Read and check a study file: schema, base model, parameter paths and values.

    Raises
    ------
    drivedyn.ModelError
        With one line naming the file, the field and the problem.
    """
    path = Path(path)
    data, text = read_toml(path, what="study")
    return study_from_dict(data, source=str(path), root=path.parent, text=text, path=path)


def study_from_dict(data: dict, source: str = "study", root=".", text: str | None = None, path=None) -> Study:
    """Validate a study given as a dict; ``base`` is resolved relative to ``root``."""
    import tomli_w

    if isinstance(data, dict) and data.get("kind") not in (None, "study"):
        raise ModelError(f"{source}: kind {data.get('kind')!r} is a model, not a study (a study has kind = \"study\" or none)")
    try:
        spec = StudySpec.model_validate(data)
    except ValidationError as exc:
        raise ModelError(f"{source}: {format_validation_error(exc, StudySpec)}") from None
    from ..core.model import load

    if spec.base is not None:
        base_path = Path(root) / spec.base
        if not base_path.exists():
            raise ModelError(f"{source}: base: model file {str(base_path)!r} not found (base is relative to the study file)")
        try:
            base = load(base_path)
        except ModelError as exc:
            raise ModelError(f"{source}: base model: {exc}") from None
    else:  # the base model written inline; file references in it are relative to the study file
        base_path = Path(path) if path is not None else Path(root) / "study.toml"
        inline = dict(spec.model)
        _absolute_files(inline, Path(root))
        base = from_dict(inline, source=f"{source}: model")
    if spec.eval_mode == "check":
        from ..core.analyses import analysis

        if not analysis(base.kind).check_data_at:
            raise ModelError(f"{source}: mode: \"check\" studies are for belt-drive models (the base is {base.kind})")
    model_cls = type(base)
    raw = to_dict(base)
    for key, value in spec.overrides.items():
        check_path(base, key, source=f"{source}: overrides")
        set_path(raw, key, value)
    # a case travels as TOML text to a worker that knows nothing of the base model's folder
    moved = _absolute_files(raw, base_path.parent)
    if spec.overrides or moved:
        try:
            base = from_dict(raw, source=f"{source}: overrides")
        except ModelError as exc:
            raise ModelError(str(exc)) from None
    units, shown = {}, {}
    for k, p in enumerate(spec.parameters):
        unit = None
        for q in p.paths:
            check_path(base, q, source=f"{source}: parameters[{k}].path")
            unit = unit if unit is not None else field_unit(model_cls, q)
        if unit is None and p.unit:
            # fields without a declared unit (table entries, plain floats) take SI values: the
            # study's unit reads strings and labels the coordinate
            try:
                to_number(f"1 {p.unit}", None)
            except ModelError:
                raise ModelError(f"{source}: parameters[{k}].unit: cannot read {p.unit!r} as a unit") from None
            unit = p.unit
        units[p.label] = unit or ""
        if unit:
            written = written_unit(list(p.values or ()) + list(p.range or ()) + [p.mean, p.std], unit)
            if written is not None and written[0] != unit:
                shown[p.label] = written
        # read every given value now, so a bad unit fails before the cluster starts
        for what in ("values", "range", "mean", "std"):
            v = getattr(p, what)
            vals = v if isinstance(v, (list, tuple)) else ([] if v is None else [v])
            for x in vals:
                try:
                    to_number(x, unit)
                except ModelError as exc:
                    raise ModelError(f"{source}: parameters[{k}].{what}: {exc}") from None
        for x in tuple(p.range or ()) + tuple(v for v in (p.mean, p.std) if v is not None):
            if not isinstance(to_number(x, unit), float):
                raise ModelError(f"{source}: parameters[{k}]: range, mean and std must be numbers, got {x!r}")
        if p.range is not None:
            lo, hi = (to_number(x, unit) for x in p.range)
            if not lo < hi:     # a reversed range left every sampled design infeasible, the study failing late
                raise ModelError(f"{source}: parameters[{k}].range: [{p.range[0]}, {p.range[1]}] is [low, high] with "
                                 f"low below high, got {lo:g} >= {hi:g}" + (f" {unit}" if unit else ""))
        if p.scale == "log" and p.range is not None:
            lo, hi = (to_number(x, unit) for x in p.range)
            if not (lo > 0 and hi > 0):
                raise ModelError(f"{source}: parameters[{k}].range: a log scale needs positive bounds, got [{lo}, {hi}]")
    if spec.optimise is not None:
        _check_bounds(spec, base, source)
    if text is None:
        text = tomli_w.dumps(data)
    return Study(spec, text, path, base_path, base, units, shown)


_WRITTEN = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*(\S.*?)\s*")


def written_unit(values, unit: str) -> tuple[str, float] | None:
    """(unit, shown value per SI value) of the first of ``values`` written with a unit that
    reads in ``unit`` proportionally ("1000 rpm" for rad/s: ("rpm", 9.549)); None if none is (plain
    numbers are SI; an offset unit such as degC is not a scale)."""
    for x in values:
        m = _WRITTEN.fullmatch(x) if isinstance(x, str) else None
        if not m:
            continue
        try:
            one, two = to_number(f"1 {m.group(1)}", unit), to_number(f"2 {m.group(1)}", unit)
        except ModelError:
            continue
        if isinstance(one, float) and one > 0 and math.isclose(two, 2 * one, rel_tol=1e-9):
            return m.group(1), 1 / one
    return None


def key_unit(units: dict, pattern: str) -> str | None:
    """The unit of the summary keys that ``pattern`` (a key, or an fnmatch pattern) names, from
    ``units`` (pattern -> unit, the first match wins, as results.unit_map): the unit of a key made
    from the pattern by writing each wildcard as a name; None when no pattern gives one."""
    import fnmatch
    import re

    specimen = re.sub(r"\[[^\]]*\]|[*?]", "x", pattern)
    return next((u for pat, u in units.items() if fnmatch.fnmatchcase(specimen, pat)), None)


def _check_bounds(spec: StudySpec, base, source: str) -> None:
    """An optimisation's constraint bounds read in the units of the keys they bound, when the study
    is read: "100 kg" on a tension is one line here, not a traceback after the first generation
    (or, where the results gave no unit, a bound silently read as 100). A key whose unit the
    analysis's unit table does not give is read against the first design's units (optimise.py)."""
    from ..core.analyses import analysis
    from ..core.units import to_si

    table = analysis(base.kind).summary_units(spec.eval_mode)
    for i, c in enumerate(spec.optimise.constraints):
        unit = key_unit(table, c.key)
        for side in ("min", "max"):
            bound = getattr(c, side)
            if bound is None:
                continue
            where = f"{source}: optimise.constraints[{i}].{side}"
            if isinstance(bound, bool) or not isinstance(bound, (int, float, str)):
                raise ModelError(f"{where}: must be a number or a quantity such as \"100 N\", got {bound!r}")
            if not isinstance(bound, str):
                continue
            try:
                if unit is None:
                    to_number(bound, None)
                else:   # "" marks a count or a name: a bound on it is a plain number
                    to_si(bound, unit or "1")
            except ModelError as exc:
                what = f" (the unit of {c.key!r} is {unit or '1'})" if unit is not None else ""
                raise ModelError(f"{where}: {exc}{what}") from None


FILE_SUFFIXES = (".toml", ".csv", ".txt", ".json", ".nc", ".dat")


def _absolute_files(node, root: Path) -> bool:
    """Make relative file references in model data absolute (in place); True if any changed.

    Models may name other files (a span model its belt-drive model, a CSV of forces), relative to
    the model file. A case is run from its TOML text alone, possibly in another folder, so such
    strings (a known file suffix and an existing file beside the base model) are made absolute.
    """
    changed = False
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for k, v in list(items):
        if isinstance(v, (dict, list)):
            changed |= _absolute_files(v, root)
        elif isinstance(v, str) and v.lower().endswith(FILE_SUFFIXES) and not Path(v).is_absolute():
            cand = (root / v)
            if cand.is_file():
                node[k] = str(cand.resolve())
                changed = True
    return changed


def check_path(model, path: str, source: str = "study") -> None:
    """Raise a one-line ModelError unless ``path`` names a field of ``model`` (data or schema)."""
    node: Any = to_dict(model)
    cls: Any = type(model)
    parts = path.split(".")
    for i, part in enumerate(parts):
        here = ".".join(parts[: i + 1])
        if isinstance(node, list):
            try:
                node = node[_index(node, part)]
            except (ValueError, IndexError):
                names = [str(x.get("name")) for x in node if isinstance(x, dict) and "name" in x]
                close = difflib.get_close_matches(part, names, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else (f" (items: {', '.join(names)})" if names else "")
                raise ModelError(f"{source}: {path!r}: no item {part!r} at {here!r}{hint}") from None
            cls = _item_class(cls)
            continue
        core = _unwrap(cls)[0] if cls is not None else None
        fields = list(getattr(core, "model_fields", {}) or {}) if isinstance(core, type) else []
        if isinstance(node, dict) and part in node:
            node = node[part]
        elif part in fields:
            node = None  # an optional field left unset in the base model: still a valid path
        else:
            keys = sorted(set(fields) | (set(node) if isinstance(node, dict) else set()))
            close = difflib.get_close_matches(part, keys, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ModelError(f"{source}: {path!r} is not a field of the base model: no {part!r} at {here!r}{hint}")
        cls = _field_class(cls, part)
    if isinstance(node, (dict,)) and node:
        raise ModelError(f"{source}: {path!r} is a whole table, not a value; name one of its fields")


def _index(node: list, part: str) -> int:
    for k, item in enumerate(node):
        if isinstance(item, dict) and item.get("name") == part:
            return k
    k = int(part)
    if not -len(node) <= k < len(node):
        raise IndexError(k)
    return k


def _field_class(cls, part):
    return schema_step(cls, part) if cls is not None else None


def _item_class(ann):
    return schema_step(ann, "0") if ann is not None else None


def to_number(value, unit: str | None):
    """A parameter value as the model will receive it: SI float for quantities, else unchanged.

    With a known field ``unit``, strings like "550 N" become 550.0. For fields without a declared
    unit (tables, plain floats) a string that starts like a number ("15 N*m") is converted to SI
    base units; any other string (an option such as "rkf45") is kept as it is.
    """
    from ..core.units import registry, to_si

    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str) and unit:
        return _tidy(to_si(value, unit))
    if isinstance(value, str) and value.strip()[:1] in set("0123456789+-."):
        try:
            q = registry().Quantity(value.strip())
            return _tidy(float(q.to_base_units().magnitude))
        except Exception:
            raise ModelError(f"cannot read {value!r} as a number with a unit") from None
    return value


def _tidy(x: float) -> float:
    """Drop the last-digit noise of unit conversion ("20 us" -> 2e-05, not 1.9999999999999998e-05),
    so that coordinates select as written."""
    return float(f"{x:.14g}")
