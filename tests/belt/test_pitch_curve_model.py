"""pulleys[].pitch_curve in the model file: validated in one line (exit 2), round trip, and what
``drivedyn check`` reports of the belt path on the curves over a turn (belt/geometry/pitch_turn.py)."""
import json
import math

import numpy as np
import pytest
from scipy.integrate import quad

import drivedyn
from drivedyn.front.cli import main
from drivedyn.mechanics.curve_turn import over_a_turn
from drivedyn.mechanics.pitch_curves import Oval

# an HTD 8M two-pulley drive (as tests/belt/test_teeth.py's), its 22-groove crank sprocket oval
HTD = """
kind = "belt-drive"
name = "HTD 8M drive, oval crank"
gravity = 0.0

[belt]
mass_per_length = "0.12 kg/m"
axial_stiffness = "1.0e5 N"
axial_damping = "0.5 N*s"
bending_stiffness = "1e-4 N*m^2"
length = "768 mm"

[belt.teeth]
profile = "HTD8M"
width = "20 mm"
play = "0 mm"
damping_ratio = 0.3

[contact]
stiffness_linear = "8e7 N/m^2"
damping = "3e4 N*s/m^2"
damping_depth = "1 mm"

[friction]
law = "threlfall"
coefficient = 0.0

[simulation]
duration = "0.5 s"

[[pulleys]]
name = "crank"
center = ["0 mm", "0 mm"]
radius = "28.0113 mm"
teeth = 22
inertia = "0.002 kg*m^2"
speed_time = [["0 s", "0 rpm"], ["0.1 s", "60 rpm"]]
[pulleys.pitch_curve]
CURVE

[[pulleys]]
name = "cam"
center = ["251.5 mm", "0 mm"]
radius = "56.0225 mm"
teeth = 44
inertia = "0.004 kg*m^2"
torque_time = [["0 s", "0 N*m"], ["0.2 s", "-10 N*m"]]
"""
OVAL = 'kind = "oval"\novality = 0.04\nphase = "20 deg"'


def _cli(tmp_path, capsys, curve, *extra):
    f = tmp_path / "m.toml"
    f.write_text(HTD.replace("CURVE", curve))
    code = main(["check", str(f), *extra])
    out = capsys.readouterr()
    return code, out.out, out.err.strip()


def _table(rows):
    return 'kind = "table"\nrows = [' + ", ".join(f'["{a} deg", "{r} mm"]' for a, r in rows) + "]"


ROUND = [(a, 28.0113) for a in range(0, 361, 30)]


@pytest.mark.parametrize("curve, says", [
    ('kind = "oval"\novality = 0.21', "curvature is -"),                                   # not convex (e > 0.2)
    ('kind = "oval"\novality = 0.21', "below 1/(n^2 + 1) = 0.2, got 0.21"),
    ('kind = "oval"\novality = 0.1\norder = 3', "convex for ovality below 1/(n^2 + 1) = 0.1, got 0.1"),
    (_table(ROUND[:-1]), "must span one turn, 360 deg: they run from 0 to 330 deg"),    # does not close the turn
    (_table(ROUND[:-1] + [(360, 28.5)]), "does not close over the turn: the radius at 360 deg (28.5 mm)"),
    (_table(ROUND[:3] + [(90, -28.0)] + ROUND[4:]), "row 3 gives a radius of -28 mm at 90 deg"),
    (_table([(a, 30.0) for a in range(0, 361, 30)]), "mean radius is 30.0000 mm but radius is 28.0113 mm"),
    ('kind = "table"\novality = 0.1\nrows = [["0 deg", "28 mm"]]', "rows"),
    ('kind = "oval"\novality = 0.1\nrows = [["0 deg", "28 mm"], ["90 deg", "28 mm"], ["180 deg", "28 mm"], '
     '["360 deg", "28 mm"]]', 'rows belong to kind = "table"'),
    ('kind = "ellipse"', "pitch_curve.kind"),
])
def test_bad_pitch_curves_one_line_exit_2(tmp_path, capsys, curve, says):
    code, out, err = _cli(tmp_path, capsys, curve)
    assert code == 2, out + err
    assert len(err.splitlines()) == 1, err
    assert "pulleys[0]" in err and "m.toml" in err and "Traceback" not in err
    assert says in err, err


def test_teeth_that_do_not_fit_the_curve_are_refused(tmp_path, capsys):
    """22 x 8 mm = 176 mm of pitch line on an oval of r0 = 28.0113 mm, ovality 0.1: its length by
    scipy's quad of sqrt(r^2 + r'^2) is 1 % longer; the radius that fits is r0 x 176 mm / P."""
    r0, e = 0.0280113, 0.1
    P = quad(lambda p: math.hypot(r0 * (1 + e * math.cos(2 * p)), 2 * r0 * e * math.sin(2 * p)), 0, 2 * math.pi,
             epsabs=1e-14)[0]
    code, out, err = _cli(tmp_path, capsys, 'kind = "oval"\novality = 0.1')
    assert code == 2 and len(err.splitlines()) == 1
    assert (f"pulleys[0].teeth: pulley 'crank' has 22 grooves of the HTD8M pitch 8 mm, 176.0000 mm of pitch line, "
            f"but its pitch curve is {P * 1e3:.4f} mm long (more than 0.5 % apart): a radius of "
            f"{r0 * 0.176 / P * 1e3:.4f} mm fits the grooves") in err


def test_the_teeth_fit_an_oval_of_the_right_radius():
    """22 x 8 mm of pitch line on an oval of ovality 0.1: r0 = 176 mm / (its perimeter per metre of r0)."""
    r0 = 0.176 / Oval(1.0, 0.1).perimeter
    m = drivedyn.loads(HTD.replace("CURVE", 'kind = "oval"\novality = 0.1').replace('"28.0113 mm"', f'"{r0 * 1e3:.6f} mm"', 1))
    assert m.pulleys[0].curve.perimeter == pytest.approx(0.176, rel=1e-6)
    assert drivedyn.loads(drivedyn.dumps(m)) == m


def test_check_reports_the_ranges_over_a_turn(tmp_path, capsys):
    code, out, err = _cli(tmp_path, capsys, OVAL)
    assert code == 0, err
    assert "pitch curves over one turn of crank" in out
    assert "Both dynamic models" in out and "drive the belt on the turning curves" in out
    code, out, err = _cli(tmp_path, capsys, OVAL, "--json")
    data = json.loads(out)["pitch_curves"]
    assert data["curves"]["crank"]["ratio"] == 1.0
    # the cam turns at the tooth ratio 22/44; the same over a turn from the mechanics directly
    turn = over_a_turn(["crank", "cam"], [(0, 0), (0.2515, 0)], [Oval(0.0280113, 0.04, math.radians(20)), 0.0560225],
                       ["inside", "inside"], ratios=[1.0, 0.5], points=180)
    span = data["spans"]["crank-cam"]
    assert (span["min"], span["max"]) == pytest.approx((turn.spans[:, 0].min(), turn.spans[:, 0].max()), abs=1e-12)
    assert span["order"] == 2
    assert span["amplitude"] == pytest.approx(turn.orders(turn.spans[:, 0])[2], rel=1e-9)
    r = data["pulleys"]["crank"]["radius_out"]
    assert 0.0280113 * 0.96 <= r["min"] < r["max"] <= 0.0280113 * 1.04
    assert data["belt_length"]["max"] - data["belt_length"]["min"] == pytest.approx(
        np.ptp(turn.length), abs=1e-12)
    assert json.loads(out)["units"]["pitch_curves.pulleys.crank.wrap.min"] == "rad"
    assert json.loads(out)["units"]["pitch_curves.spans.crank-cam.amplitude"] == "m"


def test_plot_of_the_turn(tmp_path):
    from drivedyn.belt.geometry.pitch_turn import turn_of
    from drivedyn.belt.plots import plot_pitch_turn
    from drivedyn.core.plotting import figure, savefig

    turn = turn_of(drivedyn.loads(HTD.replace("CURVE", OVAL)), points=90)
    fig, ax = figure()
    lines = plot_pitch_turn(turn, ax[0, 0])
    assert len(lines) == 3
    # the drawn change of the crank-cam span is the span's own over the turn
    assert np.ptp(lines[1].get_ydata()) == pytest.approx(np.ptp(turn.spans[:, 0]) * 1e3)
    assert savefig(fig, tmp_path / "pitch.png").stat().st_size > 0
