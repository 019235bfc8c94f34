import warnings

import pytest

import drivedyn

EXAMPLE = drivedyn.example_path("gears-split-path")


def seed_model(**changes):
    """The seed 003 split-path example with the seed's own data (mesh damping 100 N s/m, linear
    meshes, 0.2 s as in the seed's window; the shipped example assumes a damping ratio of 0.05 and
    tooth separation instead), without its sweep, with dotted-path changes."""
    m = drivedyn.load(EXAMPLE)
    over = {"sweep.enabled": False, "simulation.duration": 0.2, "sweep.settle": 0.03}
    for mesh in ("m12", "m13"):
        over.update({f"meshes.{mesh}.damping": 100.0, f"meshes.{mesh}.damping_ratio": None,
                     f"meshes.{mesh}.separation": False})
    over.update({k.replace("__", "."): v for k, v in changes.items()})
    return drivedyn.replace(m, over)


def pair_model(**changes):
    """One seed pinion driving one seed wheel (57 teeth), constant torques, no friction."""
    data = {
        "kind": "gear-train",
        "gears": [
            {"name": "p", "teeth": 21, "module": 2.5e-3, "profile_shift": 0.29, "face_width": 0.024,
             "tip_diameter": 0.058712, "inertia": 1.47e-4},
            {"name": "g", "teeth": 57, "module": 2.5e-3, "profile_shift": 0.29, "face_width": 0.024,
             "tip_diameter": 0.148712, "inertia": 7.81e-3, "load_fraction": 1.0},
        ],
        "meshes": [{"name": "m", "gears": ["p", "g"], "damping_ratio": 0.05,
                    "stiffness": {"model": "cai", "mean": 449.9e6}}],
        "drive": {"input": "p", "speed": 151.84, "torque": 24.7},
        "simulation": {"duration": 0.02, "step": 5e-6},
    }
    from drivedyn.core.model import from_dict, set_path

    for k, v in changes.items():
        set_path(data, k.replace("__", "."), v)
    return from_dict(data)


@pytest.fixture
def quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def assert_one_line_refusal(example, edit, expect, tmp_path, capsys):
    """``drivedyn check`` of ``example`` with ``edit`` = (old, new) applied to its text: exit 2 and a
    single stderr line holding ``expect``."""
    from drivedyn.front.cli import main

    good = drivedyn.example_path(example).read_text()
    old, new = edit
    assert old in good
    f = tmp_path / "m.toml"
    f.write_text(good.replace(old, new, 1))
    assert main(["check", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and expect in err, err
