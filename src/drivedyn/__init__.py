"""drivedyn: dynamics and geometry of mechanical power transmissions.

One way in::

    import drivedyn
    model = drivedyn.load("examples/belt-5pk.toml")
    result = drivedyn.run(model)
    result.summary["pulleys"]["driven"]["slip"]
    result.save("out")
"""
from ._version import __version__  # noqa: E402

from .api import check, example_path, examples, run  # noqa: E402
from .errors import DrivedynError, DrivedynWarning, ModelError, SolverError  # noqa: E402
from .model import dumps, load, loads, replace, save  # noqa: E402
from .results import Result, open_result  # noqa: E402

__all__ = [
    "__version__", "load", "loads", "save", "dumps", "replace", "run", "check", "examples",
    "example_path", "Result", "open_result", "DrivedynError", "ModelError", "SolverError",
    "DrivedynWarning",
]
