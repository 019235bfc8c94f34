"""The belt drive's run: which model integrates it (the segment model, seed 000, or the rotational
model and its periodic run-ups), chosen by ``simulation.model`` and ``simulation.runup``."""
from __future__ import annotations


def run(model, progress=None):
    """Run a belt-drive model (drivedyn.run calls it through drivedyn.core.analyses): the drive is
    resolved once (geometry/drive.py) and handed to the model that integrates it."""
    from .geometry.drive import resolve

    drive = resolve(model)
    if model.simulation.model == "rotational":
        if model.simulation.runup == "periodic":
            from .rotational.periodic import run as run_periodic

            return run_periodic(drive, progress)
        from .rotational.simulate import run as run_rotational

        return run_rotational(drive, progress)
    curved = next((k for k, p in enumerate(model.pulleys) if p.pitch_curve is not None), None)
    if curved is not None and model.simulation.method in ("implicit", "rkf45"):
        from ..core.errors import ModelError

        # the non-circular contact is in the semi-implicit scheme's contact stage (segments/_curves.py)
        raise ModelError(f"pulley {model.pulleys[curved].name!r} has a pitch curve, which the segment model drives "
                         f"with the semi-implicit scheme, not {model.simulation.method!r}: leave simulation.method "
                         "out (\"auto\") or set it to \"semi-implicit\"", field="simulation.method")
    from .segments.simulate import run as run_segments

    return run_segments(drive, progress)


def summary_units() -> dict:
    """Units of a run's summary keys (fnmatch patterns, the first match wins): the segment and
    the rotational model's."""
    from .dynamics.outputs import ROTATIONAL_UNITS, UNITS

    return {**UNITS, **ROTATIONAL_UNITS}


def lean_possible(model, keys) -> bool:
    """Whether :func:`run_lean` gives the summary keys ``keys`` (patterns) of ``model``: a periodic
    run-up of the rotational model, the keys its run-up tables (periodic.lean_keys)."""
    if model.simulation.model != "rotational" or model.simulation.runup != "periodic":
        return False
    from .rotational.periodic import lean_keys

    return lean_keys(keys) is not None


def run_lean(model, keys, progress=None):
    """A run that computes only the summary keys ``keys`` (a design loop's objective and
    constraints), with the full run's numbers; None when only the full run gives them."""
    if not lean_possible(model, keys):
        return None
    from .rotational.periodic import run as run_periodic

    from .geometry.drive import resolve

    return run_periodic(resolve(model), progress, keys=keys)


def warm():
    """Run a tiny drive for a few steps so that every kernel is loaded from numba's cache."""
    from ..core.model import from_dict

    m = from_dict({"kind": "belt-drive", "belt": {"mass_per_length": 0.1, "axial_stiffness": 1e5, "pretension": 100.0,
                                                   "segments": 24},
                   "contact": {"stiffness_linear": 1e8}, "simulation": {"duration": 2e-4},
                   "output": {"interval": 1e-4, "frames": 1},
                   "pulleys": [{"name": "a", "center": [0, 0], "radius": 0.03},
                               {"name": "b", "center": [0.2, 0], "radius": 0.03}]})
    run(m)


