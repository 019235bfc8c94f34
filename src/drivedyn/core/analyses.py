"""The analysis registry: which package answers which ``kind``, and where its entry points live.

Every analysis is a subpackage whose ``model.py`` defines ``Model``; its run, check and plot
functions are named here as ``"module:function"`` inside the package and imported only when
called, so that ``drivedyn.load`` of a belt model never imports the gear code (or numba).
"""
from __future__ import annotations

import difflib
import importlib
from dataclasses import dataclass

from .errors import ModelError


@dataclass(frozen=True)
class Analysis:
    """One analysis: ``run(model, progress=None) -> Result``, ``check(model) -> str``,
    ``plot(result, outdir) -> list[Path]``, optional ``warmup()`` (compile kernels once)."""

    kind: str
    package: str
    run_at: str
    check_at: str
    plot_at: str
    warmup_at: str = ""
    check_data_at: str = ""    # what check knows, as a dict (check --json, studies with mode = "check")
    criteria_at: str = "criteria:evaluate"   # (model, result) -> ([Criterion], {name: why not judged})
    lean_at: str = ""          # (model, keys, progress) -> Result with at least those summary keys, or None
    lean_possible_at: str = ""  # (model, keys) -> whether lean_at gives them
    # units of the summary keys, fnmatch pattern -> unit (a dict, or a function returning one), of
    # a run and of check's data: a study's constraint bounds are read against them
    units_at: str = ""
    check_units_at: str = ""
    # its plot function takes plotting.Painters forked before the solve (importing the plot module
    # to find out costs 1 s of matplotlib on the critical path of the analyses that do not)
    paints_ahead: bool = False

    def _get(self, where: str):
        module, name = where.split(":")
        return getattr(importlib.import_module(f"{self.package}.{module}"), name)

    @property
    def Model(self):
        return importlib.import_module(f"{self.package}.model").Model

    def run(self, model, progress=None):
        return self._get(self.run_at)(model, progress=progress)

    def check(self, model) -> str:
        return self._get(self.check_at)(model)

    def plot(self, result, outdir, meanwhile=None, painters=None):
        import inspect

        fn = self._get(self.plot_at)
        if painters is not None and "painters" in inspect.signature(fn).parameters:
            return fn(result, outdir, meanwhile=meanwhile, painters=painters)
        if meanwhile is not None and "meanwhile" in inspect.signature(fn).parameters:
            return fn(result, outdir, meanwhile=meanwhile)
        if meanwhile is not None:
            meanwhile()
        return fn(result, outdir)

    def painters(self, model=None):
        """plotting.Painters forked now to write this analysis's outputs after ``model``'s solve, or
        None where its plot function does not use them, its plot module's ``painters_useful(model)``
        says the solve is too short to hide their start, or forking is not possible."""
        import inspect

        from .plotting import Painters

        if not self.paints_ahead or "painters" not in inspect.signature(self._get(self.plot_at)).parameters:
            return None
        module = self.plot_at.split(":")[0]
        useful = getattr(importlib.import_module(f"{self.package}.{module}"), "painters_useful", None)
        if model is not None and useful is not None and not useful(model):
            return None
        return Painters.start(f"{self.package}.{module}")

    def lean_possible(self, model, keys) -> bool:
        """Whether :meth:`run_lean` computes the summary keys ``keys`` (patterns) of ``model``
        without the full run."""
        return bool(self.lean_possible_at) and bool(self._get(self.lean_possible_at)(model, keys))

    def run_lean(self, model, keys, progress=None):
        """A Result with the summary keys ``keys`` (patterns) and the full run's numbers for them
        (no Dataset, criteria or diagnostics but the solve's), or None when only the full run gives them."""
        return self._get(self.lean_at)(model, keys, progress=progress) if self.lean_at else None

    def summary_units(self, mode: str = "run") -> dict:
        """The units of the summary keys of a ``mode`` ("run" or "check") evaluation, as fnmatch
        pattern -> unit (the first pattern that matches a key wins; results.unit_map)."""
        where = self.check_units_at if mode == "check" else self.units_at
        if not where:
            return {}
        table = self._get(where)
        return dict(table() if callable(table) else table)

    def check_data(self, model) -> dict:
        if not self.check_data_at:
            raise ModelError(f"check data (check --json, a study's mode = \"check\") is for belt-drive models "
                             f"(this is {self.kind})")
        return self._get(self.check_data_at)(model)

    def criteria_fn(self):
        """The function that evaluates the model's [criteria] on a result, or None."""
        try:
            return self._get(self.criteria_at) if self.criteria_at else None
        except ModuleNotFoundError:
            return None

    def warmup(self) -> None:
        if self.warmup_at:
            self._get(self.warmup_at)()


ANALYSES = {a.kind: a for a in (
    Analysis("belt-drive", "drivedyn.belt", "simulate:run", "statics:report", "plots:plot_all", "simulate:warm",
             "statics:check_data", lean_at="simulate:run_lean", lean_possible_at="simulate:lean_possible",
             units_at="simulate:summary_units", check_units_at="statics:CHECK_UNITS", paints_ahead=True),
    Analysis("gear-train", "drivedyn.gears", "simulate:run", "report:report", "plots:plot_all", units_at="simulate:UNITS"),
    Analysis("span-stability", "drivedyn.span", "analysis:run", "report:report", "plots:plot_all", units_at="analysis:UNITS"),
    Analysis("toothed-mesh", "drivedyn.toothed", "analysis:run", "report:report", "plots:plot_all", units_at="analysis:UNITS"),
)}

#: kind -> analysis package (for listings)
KINDS = {kind: a.package for kind, a in ANALYSES.items()}


def analysis(kind: str) -> Analysis:
    """The registered analysis of ``kind``; a ModelError naming the field ``kind`` otherwise."""
    if kind not in ANALYSES:
        close = difflib.get_close_matches(str(kind), ANALYSES, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else f" (one of {', '.join(ANALYSES)})"
        raise ModelError(f"unknown kind {kind!r}{hint}", field="kind")
    return ANALYSES[kind]
