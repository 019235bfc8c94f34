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
from drivedyn.core.errors import ModelError
from drivedyn.core.model import from_dict

EXAMPLES = ["belt-5pk", "belt-accessory", "belt-verification", "gears-split-path", "span-t10",
            "mesh-htd8m", "mesh-l", "mesh-l-on-htd8m", "mesh-l-on-htd-9525", "mesh-load-l"]
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


# The crash classes of issue 10's hostile-user fuzz (each ended in a traceback): now one line
# naming the field, at load. A value out of the float range or the physical range is refused where
# it is read; the bounds' reasons are next to them in the code.
@pytest.mark.parametrize("name, path, bad, field", [
    ("belt-5pk", "belt.mass_per_length", float("inf"), "belt.mass_per_length"),     # ZeroDivisionError, stability_limit
    ("belt-5pk", "belt.bending_stiffness", 1e308, "belt.bending_stiffness"),        # ZeroDivisionError, build
    ("belt-5pk", "belt.axial_stiffness", "1e308 N", "belt.axial_stiffness"),
    ("belt-5pk", "pulleys.driver.center", [float("inf"), 0.0], "pulleys[0].center"),  # OverflowError, initial_state
    ("belt-accessory", "pulleys.idler.center", ["1e308 m", "0 m"], "pulleys[3].center"),  # OverflowError, layout
    ("belt-5pk", "belt.segments", 2 ** 62, "belt.segments"),                        # allocation of 4e18 segments
    ("gears-split-path", "gears.pinion.inertia", 1e-308, "gears[0].inertia"),       # OverflowError, assemble
    ("gears-split-path", "drive.speed", "1e-308 rad/s", "drive.speed"),
    ("gears-split-path", "gears.pinion.profile_shift", 1e308, "gears[0].profile_shift"),  # math domain error
    ("gears-split-path", "gears.pinion.face_width", 1e308, "gears[0].face_width"),           # ran to exit 0
    ("gears-split-path", "gears.pinion.face_width", "1e20 m", "gears[0].face_width"),
    ("gears-split-path", "drive.speed", "1e20 rpm", "drive.speed"),                 # ran to exit 0
    ("gears-split-path", "iso.sigma_hlim", 1e308, "iso.sigma_hlim"),                # OverflowError, iso6336
    ("span-t10", "span.bending_stiffness", float("inf"), "span.bending_stiffness"),  # LinAlgError, frequencies
    ("span-t10", "span.length", 1e-308, "span.length"),                             # ZeroDivisionError, euler_load
    ("span-t10", "span.density", 1e308, "span.density"),                            # LinAlgError
    ("span-t10", "tooth_force.polynomial", [float("nan"), 1.0], "tooth_force.polynomial"),  # ran to exit 0
    ("span-t10", "tooth_force.polynomial", [float("inf"), 1.0], "tooth_force.polynomial"),
    ("span-t10", "chart.zoom.points", [-5, 10], "chart.zoom.points"),               # negative count to linspace
    ("span-t10", "excitation.pulley_radius", 1e308, "excitation.pulley_radius"),    # ZeroDivisionError, point_floquet
    ("span-t10", "measurement.frequency", "1e308 Hz", "measurement.frequency"),      # OverflowError, string_tension
    ("mesh-htd8m", "maps.pitch_error", [float("nan")], "maps.pitch_error"),         # GEOSException
    ("mesh-htd8m", "maps.angles", -3, "maps.angles"),                               # negative count to linspace
    ("mesh-htd8m", "maps.teeth", [16] * 500, "maps"),                               # 500 engagement sweeps at load
    ("belt-5pk", "pulleys.driver.name", "a\x00b", "pulleys[0].name"),               # ValueError writing netCDF
])
def test_issue_10_crash_classes_are_refused_naming_the_field(name, path, bad, field):
    model = drivedyn.load(drivedyn.example_path(name))
    with pytest.raises(ModelError) as exc:
        drivedyn.replace(model, {path: bad})
    text = str(exc.value)
    assert "\n" not in text and f"override: {field}" in text, text


def test_a_model_read_back_writes_back():
    """NaN or inf cannot reach a model object, so every model that loads can be saved as TOML
    (a table holding NaN once failed after the solve, when the model was written with the results)."""
    for name in EXAMPLES:
        model = drivedyn.load(drivedyn.example_path(name))
        assert drivedyn.loads(drivedyn.dumps(model)) == model


def test_the_known_unit_factors_are_pints():
    """units.KNOWN_FACTORS (read without building the pint registry) and the identity shortcut give
    exactly the factor pint gives, for every unit the shipped examples write."""
    from drivedyn.core import units

    targets = {u for _, u in units.KNOWN_FACTORS} | {
        "N", "N*m", "N*m*s/rad", "N*m*s^2/rad^2", "N*m/rad", "N*m^2", "N*m^2*s", "N*s", "N*s/m^2",
        "N/m", "N/m^2", "N/m^3", "W", "kg", "kg*m^2", "kg/m", "kg/m^3", "m", "m/s", "m/s^2", "m^2",
        "rad/s", "s", "Hz", "Pa", "rad"}
    ureg = units.registry()
    for (text, unit), factor in list(units.KNOWN_FACTORS.items()) + [((u, u), 1.0) for u in targets]:
        assert units._factor(text, unit) == factor
        assert float(ureg.Quantity(1.0, text).to(unit).magnitude) == factor, (text, unit)


def test_a_ratio_bound_is_not_printed_with_unit_one():
    """A dimensionless field's bound read "must be >= 0 1, got -1" (its SI unit "1" printed)."""
    import drivedyn

    m = drivedyn.load(drivedyn.example_path("fead-runup"))
    try:
        drivedyn.replace(m, {"criteria.stop_clearance_min": -1})
    except drivedyn.ModelError as exc:
        assert str(exc).endswith("criteria.stop_clearance_min: must be >= 0, got -1"), str(exc)
    else:
        raise AssertionError("a negative clearance was accepted")


def test_a_refusal_is_one_line_whatever_its_message_carries():
    """A refusal that wraps another library's error text (a linear-algebra failure of a planetary
    stage with extreme stiffnesses) ended in a multi-line error: a ModelError is one line."""
    exc = ModelError("the stage's lateral modes cannot be solved: LinAlgError:\n  the leading minor\tof order 3\r\n"
                     "is not positive definite", field="planetary.lateral")
    assert str(exc) == ("planetary.lateral: the stage's lateral modes cannot be solved: LinAlgError: the leading minor "
                        "of order 3 is not positive definite")
    assert str(ModelError("plain")) == "plain"


# The newest features the same way: every value of the supplier report's duty cycle and life fit,
# the belt's catalogue data and the tensioner's supplier data (AG0868, its dynamic and tolerance
# columns off: a check in under a second), and of a planetary stage with its time integration
# (check reads it; tests/api/test_fuzz.py runs it), each replaced by one bad value.
NEWER = {"fead-ag0868": lambda p: p[0] == "duty_cycle" or (p[0] == "pulleys" and "arm" in p)
         or (p[0] == "belt" and p[1] in ("profile", "ribs", "effective_length", "length_tolerance", "wear_allowance")),
         "gears-planetary": lambda p: p[0] == "planetary"}


def _edge_values(v):
    """Values just inside the read bounds (1e-30..1e30 in SI), which reach the solvers: they found the
    life fit's overflows and the planetary kernel's divisions by zero."""
    if isinstance(v, bool) or not isinstance(v, (int, float, str)):
        return []
    if isinstance(v, str):
        if " " not in v:
            return []
        unit = v.split(" ", 1)[1]
        return [f"1e29 {unit}", f"1e-29 {unit}"]
    return [1e29, 1e-29]


@pytest.mark.parametrize("name", list(NEWER))
def test_a_bad_value_in_the_newer_sections_is_refused_cleanly(name):
    base = tomllib.loads(drivedyn.example_path(name).read_text())
    if name == "fead-ag0868":
        base["duty_cycle"].update(dynamic=False, tolerance=False)
    tried = refused = 0
    for i, (path, value) in enumerate(_leaves(base)):
        if not NEWER[name](path) or path[-1] in ("dynamic", "tolerance"):
            continue
        for bad in _edge_values(value):
            data = copy.deepcopy(base)
            _set(data, path, bad)
            tried += 1
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    drivedyn.check(from_dict(data, source=name))
            except ModelError as exc:
                refused += 1
                assert "\n" not in str(exc).strip(), (path, bad, str(exc))
            except Exception as exc:  # pragma: no cover - the failure message is the point
                pytest.fail(f"{name}: {'.'.join(map(str, path))} = {bad!r}: {type(exc).__name__}: {exc}")
    assert tried >= 20 and refused >= tried // 3, (tried, refused)
