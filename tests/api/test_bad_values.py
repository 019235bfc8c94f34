"""Robustness over every shipped example: any single value replaced by a bad one (negative, zero,
absurdly large, not a number, wrong unit) either still makes a valid model or is refused with a
ModelError (one line, exit status 2 on the command line); never another exception in load or
check. Each value gets one plain replacement and, for a quantity, one with its unit, cycled over
the values so that the suite stays fast. Full sweeps of every replacement over every value (load,
check and short runs) found what this guards: a tiny pretension, a huge bending damping, friction
coefficient or mass uncertainty, a comparison row with 0 teeth, a meshing sample spacing of 1e-12 m
(a run that never ends)."""
import copy
import tomllib
import warnings

import pytest

import drivedyn
from drivedyn.errors import ModelError
from drivedyn.model import from_dict

EXAMPLES = ["belt-5pk", "belt-accessory", "belt-verification", "gears-split-path", "span-t10",
            "mesh-htd8m", "mesh-l", "mesh-l-on-htd8m"]
PLAIN = [-1, 0, "abc", 1e30, [], {"x": 1}]


def _leaves(d, path=()):
    if isinstance(d, dict):
        for k, v in d.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(d, list) and d:
        for i, v in enumerate(d):
            yield from _leaves(v, path + (i,))
    else:
        yield path, d


def _set(d, path, v):
    for p in path[:-1]:
        d = d[p]
    d[path[-1]] = v


def _bad_values(i, v):
    out = [PLAIN[i % len(PLAIN)]]
    if isinstance(v, str) and " " in v:  # a quantity with its unit
        num, unit = v.split(" ", 1)
        out += [[f"-{num} {unit}", f"0 {unit}", f"1e9 {unit}", f"1e-9 {unit}", f"{num} kg*s"][i % 5]]
    return out


@pytest.mark.parametrize("name", EXAMPLES)
def test_a_bad_value_anywhere_is_refused_cleanly(name):
    base = tomllib.loads(drivedyn.example_path(name).read_text())
    tried = 0
    for i, (path, value) in enumerate(_leaves(base)):
        if path[0] in ("kind", "schema_version", "name"):
            continue
        for bad in _bad_values(i, value):
            data = copy.deepcopy(base)
            _set(data, path, bad)
            tried += 1
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    drivedyn.check(from_dict(data, source=name))
            except ModelError as exc:
                assert "\n" not in str(exc).strip(), (path, bad, str(exc))
            except Exception as exc:  # pragma: no cover - the failure message is the point
                pytest.fail(f"{name}: {'.'.join(map(str, path))} = {bad!r}: {type(exc).__name__}: {exc}")
    assert tried >= 10


@pytest.mark.parametrize("name, path, bad", [
    ("belt-verification", "belt.pretension", "1e-9 N"),             # gap at round-off: placement
    ("belt-5pk", "belt.bending_damping", "1e9 N*m^2*s"),              # stable step ~ 0
    ("belt-5pk", "friction.coefficient", 1e30),                       # capstan e^(mu theta) overflow
    ("span-t10", "measurement.mass_uncertainty", "1e9 kg/m"),         # derivative step from sigma
    ("mesh-htd8m", "mesh.flank_spacing", "1e-9 mm"),                  # 1e10 samples: refused
    ("mesh-htd8m", "mesh.chord_tolerance", "1e-9 mm"),
])
def test_values_that_once_raised_tracebacks(name, path, bad):
    model = drivedyn.load(drivedyn.example_path(name))
    try:
        model = drivedyn.replace(model, {path: bad})
        drivedyn.check(model)
    except ModelError as exc:
        assert "\n" not in str(exc).strip()


def test_comparison_row_with_too_few_teeth_names_the_field():
    data = tomllib.loads(drivedyn.example_path("mesh-htd8m").read_text())
    data["compare"][0]["teeth"] = 0
    with pytest.raises(ModelError, match="teeth"):
        from_dict(data, source="mesh")
