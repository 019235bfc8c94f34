import copy
import sys
from pathlib import Path

import pytest

from drivedyn.core.model import from_dict

# tests that reuse a benchmark's drive (bench_fead_convergence.held, bench_chord_sag.drive,
# bench_rotational_agreement.three_pulleys) import it
sys.path.insert(0, str(Path(__file__).parents[2] / "benchmarks"))

BASE = {
    "kind": "belt-drive",
    "belt": {"mass_per_length": 0.096, "axial_stiffness": 1.52e5, "axial_damping": 0.164,
             "bending_stiffness": 2.08e-4, "pretension": 550.0, "segments": 100},
    "contact": {"stiffness_linear": 8.125e7, "stiffness_quadratic": 3.782e11, "damping": 3.75e4, "damping_depth": 1e-3},
    "friction": {"law": "threlfall", "coefficient": 1.0, "velocity_threshold": 1e-5},     # the seed's law
    "gravity": 0.0,
    "simulation": {"duration": 0.3},
    "output": {"interval": 1e-3, "frames": 10},
    "pulleys": [
        {"name": "driver", "center": [0.0, 0.0], "radius": 0.027, "inertia": 0.02},
        {"name": "driven", "center": [0.515, 0.0], "radius": 0.027, "inertia": 0.02},
    ],
}


def make(**changes):
    """The two-pulley 5PK drive of the seed (100 segments, no gravity, Threlfall's law) with dotted-path
    changes."""
    from drivedyn.core.model import set_path

    data = copy.deepcopy(BASE)
    for path, value in changes.items():
        set_path(data, path.replace("__", "."), value)
    return from_dict(data)


def seed_5pk(**over):
    """examples/belt-5pk.toml at the seed's 150 segments and the semi-implicit scheme, as the seed's
    figures and the measurements quoted in these tests were taken (the example itself runs at
    "auto"), with dotted-path changes."""
    import drivedyn

    return drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                            {"belt.segments": 150, "simulation.method": "semi-implicit", "output.segments": [107],
                             **over})


@pytest.fixture(scope="session")
def model_factory():
    return make
