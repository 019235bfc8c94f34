"""The shipped example models (drivedyn/examples_data, inside the package so that it works after
pip install), by name."""
from __future__ import annotations

from pathlib import Path

from .errors import ModelError


def examples_dir() -> Path:
    """Folder of the shipped example models (inside the package, so it works after pip install)."""
    return Path(__file__).parent.parent / "examples_data"


def examples() -> dict[str, Path]:
    """Shipped example models by name."""
    return {p.stem: p for p in sorted(examples_dir().glob("*.toml"))}


def example_path(name: str) -> Path:
    """Path of a shipped example model, e.g. ``example_path("belt-5pk")``."""
    ex = examples()
    if name.removesuffix(".toml") not in ex:
        raise ModelError(f"no example named {name!r} (have: {', '.join(ex)})")
    return ex[name.removesuffix(".toml")]
