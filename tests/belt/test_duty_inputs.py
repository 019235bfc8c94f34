"""The supplier report's inputs under bad values (belt/steady/duty.py, life.py, geometry/positions.py):
each either reads right or is refused in one line naming the field and the numbers, never a
traceback, a silent no-op or a life that passes by overflow."""
import math

import pytest

import drivedyn
from drivedyn.core.errors import ModelError


def _ag0868(**changes):
    """The AG0868 example, its dynamic and tolerance columns off (the static report only), changed."""
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    return drivedyn.replace(model, {"duty_cycle.dynamic": False, "duty_cycle.tolerance": False, **changes})


def _refused(change, *words):
    with pytest.raises(ModelError) as info:
        drivedyn.check(_ag0868(**change))
    text = str(info.value)
    assert "\n" not in text and all(w in text for w in words), text
    return text


def test_a_duty_rows_load_on_the_crank_is_refused_like_an_unknown_pulley():
    """The crank's torque is the balance of the others' (steady/duty.py): a power on it changed
    nothing, silently."""
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    for value in ({"CRK": "2 kW"}, {"A_C": "1.3 kW", "CRK": "2 kW"}):
        with pytest.raises(ModelError) as info:
            drivedyn.replace(model, {"duty_cycle.rows.0.power": value})
        text = str(info.value)
        assert "duty_cycle.rows[0].power" in text and "'CRK' is the crank" in text and "A_C, TEN" in text, text
    with pytest.raises(ModelError, match=r"duty_cycle.rows\[0\].torque: pulley 'CRK' is the crank"):
        drivedyn.replace(model, {"duty_cycle.rows.0.torque": {"CRK": "10 N*m"}})
    with pytest.raises(ModelError, match=r"duty_cycle.rows\[0\].power: no pulley named 'XYZ'"):
        drivedyn.replace(model, {"duty_cycle.rows.0.power": {"XYZ": "1 W"}})


@pytest.mark.parametrize("offset, where", [("60 mm", "beyond the free arm"), ("-60 mm", "beyond the load stop")])
def test_a_belt_length_offset_the_drawn_arm_cannot_hold_is_refused(offset, where):
    """The mean row read 1079.69 (959.69) mm of required belt for a 1020 mm belt and the duty cycle
    went on unchanged; the docs say a tensioner that cannot hold the belt's band is refused."""
    text = _refused({"belt.length_offset": offset}, "belt.length_offset", "1020.00 mm belt", where)
    assert ("959.69" if offset == "60 mm" else "1079.69") in text


def test_a_length_offset_within_the_band_still_reads():
    data = drivedyn.core.analyses.analysis("belt-drive").check_data(_ag0868(**{"belt.length_offset": "0.3 mm"}))
    assert data["supplier"]["belt"]["required_length"] == pytest.approx(1.01939, abs=2e-5)


@pytest.mark.parametrize("change, words", [
    ({"duty_cycle.temperature": 1e6}, ("duty_cycle.temperature", "[-60, 250]")),           # OverflowError
    ({"duty_cycle.life.halving": 1e-20}, ("duty_cycle.life", "halving", "[1, 1000]")),       # OverflowError
    ({"duty_cycle.life.reference_temperature": 1e29}, ("reference_temperature", "[-60, 250]")),  # B10 inf passed
    ({"duty_cycle.life.constant": 1e29}, ("duty_cycle.life", "B10 = 1.619e+37 h", "outside 1e-30..1e30 h")),
    ({"duty_cycle.life.exponent": 1e29}, ("exponent", "(0, 20]")),
    ({"duty_cycle.life.tension_exponent": -1}, ("tension_exponent", "[0, 10]")),
])
def test_the_life_fit_is_refused_outside_its_domain(change, words):
    _refused(change, *words)


def test_an_infinite_life_never_passes_the_target():
    """B10 = C / D with a damage sum that underflows was inf, and inf >= target passed."""
    from drivedyn.belt.steady.life import belt_life

    model = _ag0868(**{"duty_cycle.life.constant": 1e-30, "duty_cycle.life.exponent": 20.0})
    life = belt_life(model, 355.9, [7.4] * len(model.duty_cycle.rows))
    assert math.isfinite(life.b10_hours) and sum(life.pulley_share.values()) == pytest.approx(1.0)
    with pytest.raises(ModelError, match="outside 1e-30..1e30 h"):
        belt_life(_ag0868(**{"duty_cycle.life.constant": 1e30}), 1e-9, [7.4] * len(model.duty_cycle.rows))


def test_the_life_in_logarithms_is_the_fits_formula():
    """The log-space sum gives the fit's B10 written out (steady/life.py's docstring)."""
    from drivedyn.belt.geometry.catalogue import effective_diameters
    from drivedyn.belt.steady.life import belt_life

    model = _ag0868()
    fit, dc = model.duty_cycle.life, model.duty_cycle
    speeds = [5.0 + k for k in range(len(dc.rows))]
    d = effective_diameters(model) * 1e3
    g = sum((fit.back_side_weight if p.side == "back" else 1.0) * x ** -fit.exponent for p, x in zip(model.pulleys, d))
    rows = sum(r.share * v / model.belt.effective_length * 2 ** ((dc.temperature - fit.reference_temperature) / fit.halving)
               for r, v in zip(dc.rows, speeds))
    b10 = fit.constant / (g * rows * (350.0 / model.belt.ribs) ** fit.tension_exponent)
    assert belt_life(model, 350.0, speeds).b10_hours == pytest.approx(b10, rel=1e-12)


def _rows(n):
    return [{"crank_speed": f"{800 + k % 1200} rpm", "share": 1.0 / n, "power": {"A_C": "1.5 kW"}} for k in range(n)]


@pytest.mark.parametrize("n, tolerance", [(2001, False), (401, True)])
def test_a_duty_cycle_beyond_the_balances_limit_is_refused_before_its_rows_are_read(n, tolerance):
    """10 000 static rows (within the list limit) took about 11 minutes of check."""
    import time

    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    t0 = time.process_time()
    with pytest.raises(ModelError) as info:
        drivedyn.replace(model, {"duty_cycle": {"rows": _rows(n), "tolerance": tolerance}})
    text = str(info.value)
    assert "duty_cycle: rows:" in text and "steady balances" in text and "DRIVEDYN_MAX_BALANCES" in text, text
    assert f"{n * (5 if tolerance else 1)} steady balances" in text and "\n" not in text
    assert time.process_time() - t0 < 2.0


def test_the_balances_limit_is_read_from_the_environment(monkeypatch):
    monkeypatch.setenv("DRIVEDYN_MAX_BALANCES", "5")       # the example's 6 rows at 5 belt lengths: 30
    with pytest.raises(ModelError, match="30 steady balances of duty rows, more than the 5"):
        drivedyn.load(drivedyn.example_path("fead-ag0868"))
    monkeypatch.setenv("DRIVEDYN_MAX_BALANCES", "inf")
    assert len(drivedyn.load(drivedyn.example_path("fead-ag0868")).duty_cycle.rows) == 6


def test_the_held_rows_steps_together_are_refused_before_any_row_is_solved(monkeypatch):
    """2000 dynamic rows under DRIVEDYN_MAX_STEPS = 1e6 ran (each row's run fits; together 30 x over)."""
    from drivedyn.belt.steady import duty

    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "3e4")        # each held row: 5400 steps; the six: 32 400
    monkeypatch.setattr(duty, "duty_cycle", lambda *a, **k: pytest.fail("the static rows were solved first"))
    model = _ag0868(**{"duty_cycle.dynamic": True})
    with pytest.raises(ModelError) as info:
        drivedyn.check(model)
    text = str(info.value)
    assert "duty_cycle.dynamic: 3.24e+04 integration steps" in text and "6 held rows of 5400 steps" in text, text


def test_a_free_arm_at_the_drawn_arm_names_the_stops_not_the_belt_order():
    """A free arm 0.001 deg from the drawn arm (the belt installed by its part sits at another arm
    angle): that read "the belt order does not make a simple loop"; now one line on the free arm."""
    text = _refused({"pulleys.2.arm.free_angle": "220.001 deg"}, "free_angle")
    assert not text.split(": ", 1)[-1].startswith("pulleys: the belt order")


def test_the_kind_cannot_change_through_an_override(capsys):
    """--set kind=gear-train listed 20 problems of a belt model read as a gear train."""
    from drivedyn.front.cli import main

    code = main(["check", str(drivedyn.example_path("belt-5pk")), "--set", "kind=gear-train"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and "kind: the kind of a model cannot change" in err, err
    assert "more problems" not in err
    assert main(["check", str(drivedyn.example_path("belt-5pk")), "--set", "kind=belt-drive"]) == 0


def test_a_pivot_inside_another_pulley_is_refused():
    """A pivot 67 mm from the crank's centre (radius 88.7 mm) was accepted and the arm drawn through it."""
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    with pytest.raises(ModelError) as info:
        drivedyn.replace(model, {"pulleys.2.arm.pivot": ["67 mm", "0 mm"], "pulleys.2.arm.free_angle": None,
                                 "pulleys.2.arm.free_torque": None, "pulleys.2.arm.load_stop": None})
    text = str(info.value)
    assert "pulleys[2].arm.pivot" in text and "inside pulley 'CRK' (67 mm from its centre, radius 88.71 mm)" in text, text


@pytest.mark.parametrize("rate, per_rad", [("0.4 N*m/deg", 0.4 * 180 / math.pi), ("0.4 N*m/rad", 0.4), (0.4, 0.4)])
def test_a_torsional_rate_reads_per_its_angle(rate, per_rad):
    model = _ag0868(**{"pulleys.2.arm.rate": rate})
    assert model.pulleys[2].arm.rate == pytest.approx(per_rad, rel=1e-12)


def test_a_torsional_rate_without_an_angle_in_its_unit_is_refused():
    """"0.4 N*m" read per radian: a spring 57 times softer than meant, and every duty row failed."""
    with pytest.raises(ModelError) as info:
        _ag0868(**{"pulleys.2.arm.rate": "0.4 N*m"})
    text = str(info.value)
    assert "pulleys[2].arm.rate" in text and "no angle in its unit" in text and "'0.4 N*m/deg'" in text, text


def test_check_says_what_a_pulleys_power_takes_at_its_speed():
    """A pulley's power is an alternator's electrical output with a cut-in (a pump given 500 W carried
    23 W at 1000 rpm): check says so, with the shaft power it takes at its speed."""
    text = drivedyn.check(drivedyn.load(drivedyn.example_path("fead-runup")))
    line = next(ln for ln in text.splitlines() if "alternator.power" in ln)
    assert "electrical output" in line and "cut_in_speed 1003 rpm" in line and "769.2 W of shaft power" in line, line


def _belt_bounds():
    model = _ag0868()
    crank = next(p for p in model.pulleys if p.speed_time is not None)
    ea, m = model.belt.axial_stiffness, model.belt.mass_per_length
    return model, crank, ea, math.sqrt(ea / m)


def test_a_duty_rows_speed_past_the_belts_wave_speed_is_refused():
    """A 1e29 rpm row was solved and marked "no running balance". The bound is where the
    centrifugal tension m v^2 alone equals EA: v = sqrt(EA / m) (1256 m/s here, 135 000 rpm)."""
    _, crank, _, c = _belt_bounds()
    for rpm in ("1e29 rpm", f"{1.01 * c / crank.radius * 30 / math.pi} rpm"):
        text = _refused({"duty_cycle.rows.1.crank_speed": rpm}, "duty_cycle.rows[1].crank_speed", "sqrt(EA / m)",
                        f"{c:.4g} m/s")
        assert "stretch it by its own length" in text
    # just below it the row is read and solved: creep theory marks it not carried (the belt lifts off)
    data = drivedyn.check(_ag0868(**{"duty_cycle.rows.1.crank_speed": f"{0.99 * c / crank.radius * 30 / math.pi} rpm"}))
    assert "duty_rows_carried" in data


@pytest.mark.parametrize("what, value, words", [
    ("power", lambda v, ea, r: f"{1.01 * ea * v} W", "duty_cycle.rows[0].power: "),
    ("torque", lambda v, ea, r: f"{1.01 * ea * r} N*m", "duty_cycle.rows[0].torque: "),
])
def test_a_duty_rows_load_past_the_belts_stiffness_is_refused(what, value, words):
    """A row's load asks the span for P / v (or M / r): at EA the span would be stretched by its
    own length."""
    model, crank, ea, _ = _belt_bounds()
    v = model.duty_cycle.rows[0].crank_speed * crank.radius
    r = next(p.radius for p in model.pulleys if p.name == "A_C")
    text = _refused({"duty_cycle.rows.0.power": {}, f"duty_cycle.rows.0.{what}": {"A_C": value(v, ea, r)}}, words,
                    "pulley 'A_C'", f"EA = {ea:.4g} N")
    assert "stretched by its own length" in text


def test_a_duty_cycles_acceleration_past_the_belts_stiffness_is_refused():
    model, crank, ea, _ = _belt_bounds()
    per = sum(p.inertia * crank.radius / p.radius ** 2 for p in model.pulleys if p is not crank)
    _refused({"duty_cycle.acceleration": f"{1.01 * ea / per} rad/s^2"}, "duty_cycle.acceleration", "their inertias")
    drivedyn.check(_ag0868(**{"duty_cycle.acceleration": f"{0.5 * ea / per} rad/s^2"}))


def test_the_command_line_refuses_a_1e29_rpm_row_in_one_line(tmp_path):
    import subprocess
    import sys

    p = subprocess.run([sys.executable, "-m", "drivedyn", "check", str(drivedyn.example_path("fead-ag0868")),
                        "--set", "duty_cycle.rows.0.crank_speed=1e29 rpm"], capture_output=True, text=True,
                       timeout=120, check=False)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert "duty_cycle.rows[0].crank_speed: 1e+29 rpm" in p.stderr
