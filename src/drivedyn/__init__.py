"""drivedyn: dynamics and geometry of mechanical power transmissions.

One way in::

    import drivedyn
    model = drivedyn.load("examples/belt-5pk.toml")
    result = drivedyn.run(model)
    result.summary["pulleys"]["driven"]["slip"]
    result.save("out")
"""
from ._version import __version__
from .core.errors import DrivedynError, DrivedynWarning, ModelError, SolverError

# the rest is imported on first use (PEP 562), so that `drivedyn --help` and `import drivedyn.front.cli`
# do not import pydantic, the model classes and numpy before a command needs them
_LAZY = {"check": "api", "example_path": "api", "examples": "api", "run": "api",
         "dumps": "core.model", "load": "core.model", "loads": "core.model", "replace": "core.model",
         "save": "core.model", "Result": "core.results", "open_result": "core.results"}

__all__ = [
    "__version__", "load", "loads", "save", "dumps", "replace", "run", "check", "examples",
    "example_path", "Result", "open_result", "DrivedynError", "ModelError", "SolverError",
    "DrivedynWarning",
]


def __getattr__(name):
    import importlib
    import importlib.util

    module = _LAZY.get(name)
    if module is None:
        # a submodule (`drivedyn.core.model.to_dict` after `import drivedyn`, as when they were imported eagerly)
        if not name.startswith("__") and importlib.util.find_spec(f"{__name__}.{name}") is not None:
            return importlib.import_module(f".{name}", __name__)
        raise AttributeError(f"module 'drivedyn' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
