"""The public entry points shared by every analysis: run, check, plot, examples."""
from __future__ import annotations

from pathlib import Path

from .model import analysis, load


def _as_model(model):
    if isinstance(model, (str, Path)):
        return load(model)
    return model


def run(model, progress=None):
    """Run any model (object or path) and return its :class:`~drivedyn.Result`.

    ``progress``, if given, is called as ``progress(fraction_done, text)`` during long runs.
    A solve that fails raises :class:`~drivedyn.SolverError` whose ``partial`` holds the Result
    computed so far (``success=False``).
    """
    model = _as_model(model)
    return analysis(model.kind).run(model, progress=progress)


def check(model) -> str:
    """Validate a model and return a text report of what is known without running it."""
    model = _as_model(model)
    return analysis(model.kind).check(model)


def plot(result, outdir) -> list[Path]:
    """Write the standard PNG plots of a Result into ``outdir``; returns the files written."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return analysis(result.kind).plot(result, outdir)


def examples_dir() -> Path:
    """Folder of the shipped example models (inside the package, so it works after pip install)."""
    return Path(__file__).parent / "examples_data"


def examples() -> dict[str, Path]:
    """Shipped example models by name."""
    return {p.stem: p for p in sorted(examples_dir().glob("*.toml"))}


def example_path(name: str) -> Path:
    """Path of a shipped example model, e.g. ``example_path("belt-5pk")``."""
    from .errors import ModelError

    ex = examples()
    if name.removesuffix(".toml") not in ex:
        raise ModelError(f"no example named {name!r} (have: {', '.join(ex)})")
    return ex[name.removesuffix(".toml")]
