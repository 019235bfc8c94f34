"""The public entry points shared by every analysis: run, check, plot, examples."""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

from .core.errors import ModelError, SolverError
from .core.examples import example_path, examples, examples_dir  # noqa: F401  (the public API)
from .core.model import analysis, load


def _as_model(model):
    if isinstance(model, (str, Path)):
        return load(model)
    return model


@contextmanager
def _naming(model):
    """Errors found after loading (while assembling the model) name the file it came from."""
    try:
        yield
    except ModelError as exc:
        if isinstance(model, (str, Path)) and not str(exc).startswith(str(model)):
            raise ModelError(f"{model}: {exc}") from None
        raise


def run(model, progress=None):
    """Run any model (object or path) and return its :class:`~drivedyn.Result`.

    ``progress``, if given, is called as ``progress(fraction_done, text)`` during long runs.
    ``result.status`` is "success", or "warning" when ``result.diagnostics`` say the result is
    outside the model's valid regime. ``result.summary["verdict"]`` ("pass", "fail", "not judged")
    and ``result.summary["criteria"]`` judge it against the model's ``[criteria]``. A solve that fails raises :class:`~drivedyn.SolverError`
    whose ``partial`` holds the Result computed so far (status "failed").
    """
    from .core.criteria import judge

    m = _as_model(model)
    with _naming(model):
        try:
            result = analysis(m.kind).run(m, progress=progress)
        except SolverError as exc:
            if exc.partial is not None:
                judge(m, exc.partial)          # verdict "not judged": the run did not finish
            raise
        return judge(m, result)


def check(model) -> str:
    """Validate a model and return a text report of what is known without running it."""
    m = _as_model(model)
    with _naming(model):
        return analysis(m.kind).check(m)


def plot(result, outdir, meanwhile=None, painters=None) -> list[Path]:
    """Write the standard PNG plots of a Result into ``outdir``; returns the files written.
    ``meanwhile()`` runs while they are drawn where the analysis draws in other processes (belt
    drives), else first. ``painters`` (from :func:`painters`) are the processes that draw them."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return analysis(result.kind).plot(result, outdir, meanwhile=meanwhile, painters=painters)


def painters(kind: str, model=None):
    """Processes forked now, before a solve of ``kind`` (of ``model``, when given), that load the
    plotting libraries while it runs and then write its outputs (a ``plotting.Painters``; close it
    after use), or None where the analysis draws in this process."""
    return analysis(kind).painters(model)
