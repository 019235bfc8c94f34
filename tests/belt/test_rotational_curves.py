"""Non-circular grooved pulleys in the rotational model (rotational/curves.py): an oval of ovality 0
reproduces the round drive, the driven sprocket's speed follows the effective radii of the turning
oval (quasi-static kinematics of an inextensible belt), and an oval crank sprocket whose ovality and
phase are derived in the test from the path's length modulation cancels a cam torque's order in the
tight span."""
import math
import subprocess
import sys

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.dynamics.phase import orders_of
from drivedyn.mechanics.curve_layout import layout_at
from drivedyn.mechanics.pitch_curves import Oval
from drivedyn.mechanics.teeth.loadshare import teeth_in_mesh

R1, R2, X = 28.0113e-3, 56.0225e-3, 251.5e-3       # 22 and 44 grooves of HTD 8M

DRIVE = """
kind = "belt-drive"
name = "HTD 8M drive, oval crank sprocket (rotational)"
gravity = 0.0

[belt]
mass_per_length = "0.12 kg/m"
axial_stiffness = "EA N"
axial_damping = "20 N*s"
length = "768 mm"

[belt.teeth]
profile = "HTD8M"
width = "20 mm"
play = "0 mm"
tooth_stiffness = "KT N/m"

[contact]
stiffness_linear = "8e7 N/m^2"

[friction]
law = "threlfall"
coefficient = 0.0

[simulation]
model = "rotational"
duration = "0.8 s"

[output]
interval = "0.5 ms"
steady_window = ["0.4 s", "0.8 s"]

[[pulleys]]
name = "crank"
center = ["0 mm", "0 mm"]
radius = "28.0113 mm"
teeth = 22
inertia = "0.002 kg*m^2"
speed_time = [["0 s", "0 rpm"], ["0.1 s", "300 rpm"]]
CURVE

[[pulleys]]
name = "cam"
center = ["XC mm", "0 mm"]
radius = "56.0225 mm"
teeth = 44
inertia = "0.004 kg*m^2"
torque = "-2 N*m"
LOAD
"""


def _oval(e, phase=0.0):
    return f'[pulleys.pitch_curve]\nkind = "oval"\novality = {e}\nphase = "{phase} rad"' if e is not None else ""


def _path(e, phase, x, theta):
    curves = [Oval(R1, e, phase, 2), R2]
    return layout_at(["crank", "cam"], np.array([[0, 0], [x, 0]]), curves, ["inside", "inside"],
                     angles=np.array([theta, 0.0]))


def _model(tmp_path, e=None, phase=0.0, EA=1e5, kt=1e9, load="", x=X):
    text = (DRIVE.replace("EA", f"{EA:g}").replace("KT", f"{kt:g}").replace("XC", f"{x * 1e3:.9f}")
            .replace("CURVE", _oval(e, phase)).replace("LOAD", load))
    path = tmp_path / "m.toml"
    path.write_text(text)
    return drivedyn.load(path)


def test_an_oval_of_ovality_0_reproduces_the_round_drive(tmp_path):
    round_ = drivedyn.run(_model(tmp_path))
    oval = drivedyn.run(_model(tmp_path, e=0.0))
    a, b = round_.ds["span_tension"].values, oval.ds["span_tension"].values
    assert np.max(np.abs(a - b)) < 1e-9 * np.max(a)
    assert np.max(np.abs(round_.ds["speed"].values - oval.ds["speed"].values)) < 1e-9 * 300 * math.pi / 30


def test_the_driven_sprocket_follows_the_ovals_effective_radii(tmp_path):
    """A stiff belt on stiff teeth, the crank at a constant 300 rpm, the cam free of load: the two equal
    spans hold the cam between them, and an inextensible belt's quasi-static kinematics give its speed
    omega (h_out + h_in) / (2 r_cam), h the oval's effective radii (the spans' distances from its centre,
    mechanics/curve_layout.py) where the belt leaves and arrives; the fluctuation's order is the curve's."""
    e = 0.02
    x = _match_length(e, 0.0, 1e9)
    model = drivedyn.replace(_model(tmp_path, e=e, EA=1e9, kt=1e10, x=x), {"pulleys.cam.torque": 0.0})
    res = drivedyn.run(model)
    ds = res.ds
    sel = ds["time"].values > 0.4
    th, om = ds["angle"].values[sel, 0], ds["speed"].values[sel]
    ratio = om[:, 1] / om[:, 0]
    pred = np.array([(lay.spans[0].radius0 + lay.spans[1].radius1) / (2 * R2)
                     for lay in (_path(e, 0.0, x, t) for t in th)])
    amp = 0.5 * (pred.max() - pred.min())
    assert amp > 0.005                                  # a fluctuation of 1 % of the ratio to follow
    assert np.max(np.abs(ratio - pred)) < 0.15 * amp, (np.max(np.abs(ratio - pred)), amp)
    top = orders_of(th, ratio)[0]
    assert top["order"] == 2.0 and top["amplitude"] == pytest.approx(amp, rel=0.15)


def _match_length(e, phase, EA, T=300.0):
    """The centre distance at which the path on the oval at angle 0 holds 96 pitches at tension T."""
    from scipy.optimize import brentq

    return brentq(lambda x: _path(e, phase, x, 0.0).length - 0.768 * (1 + T / EA), 0.24, 0.26)


def test_an_oval_crank_sprocket_cancels_a_cam_torques_order(tmp_path):
    """The cam carries A sin(4 theta_cam + psi), the crank's 2nd order. Quasi-statically the free cam
    balances it by the spans' difference, T_tight - T_slack = sigma M / r_cam (sigma the belt's sense), and
    the tight span carries T_mean + sigma M / (2 r_cam); an oval crank modulates the path's length by e |G| cos(2 theta + 2 p - alpha)
    (G from the common tangents at a small ovality, linear in e), which the belt takes as stretch over
    its spans and the free pieces at the wrap ends, C = (sum L + ends) / EA: T_mean's order 2 is that
    length over C. The ovality e = A C / (2 r_cam |G|) at the phase 2 p = alpha + psi + sigma pi / 2 cancels the
    tight span's order 2: the run's order-2 amplitude within 10 % of the round sprocket's."""
    EA, A, psi = 1e5, 1.5, 0.4
    load = f'harmonics = [{{ order = 4, amplitude = "{A} N*m", phase = "{psi} rad" }}]'
    # the path's length against the crank's angle at a small ovality: its 2nd order, per unit ovality
    e0 = 1e-3
    th = np.linspace(0, math.pi, 64, endpoint=False)
    dL = np.array([_path(e0, 0.0, X, t).length for t in th]) - _path(1e-12, 0.0, X, 0.0).length
    a, b = 2 / len(th) * np.sum(dL * np.cos(2 * th)) / e0, 2 / len(th) * np.sum(dL * np.sin(2 * th)) / e0
    G, alpha = math.hypot(a, b), math.atan2(b, a)
    lay = _path(1e-12, 0.0, X, 0.0)
    pitch = 8e-3
    ends = sum(lay.arc[j] - (teeth_in_mesh(z, lay.wrap[j]) - 1) * pitch for j, z in ((0, 22), (1, 44)))
    C = (lay.spans[0].length + lay.spans[1].length + ends) / EA
    e = A * C / (2 * R2 * G)
    # the belt's sense on the pulleys (sigma: +1 counter-clockwise round them) signs the cam's balance:
    # T_tight - T_slack = sigma M / r_cam
    sigma = lay.orientation
    p = 0.5 * (alpha + psi + sigma * 0.5 * math.pi)
    assert 0.002 < e < 0.1

    def order2(model):
        res = drivedyn.run(model)
        assert res.success, res.message
        ds = res.ds
        sel = ds["time"].values > 0.4
        fit = orders_of(ds["angle"].values[sel, 0], ds["span_tension"].sel(span="crank-cam").values[sel])
        return next(o["amplitude"] for o in fit if o["order"] == 2.0) if any(o["order"] == 2.0 for o in fit) else 0.0

    round_ = order2(_model(tmp_path, EA=EA, load=load))
    assert round_ == pytest.approx(A / (2 * R2), rel=0.05)         # the quasi-static tight span's share
    x = _match_length(e, p, EA)
    oval = order2(_model(tmp_path, e=e, phase=p, EA=EA, load=load, x=x))
    print(f"order 2 of the tight span: round {round_:.3f} N, oval (e = {e:.5f}, phase {p:.4f} rad) {oval:.3f} N")
    assert oval < 0.1 * round_, (oval, round_, e, p)


def _smooth_5pk(law, e=None, sense=1.0):
    """The 5PK friction drive (examples/belt-5pk.toml) in the rotational model, its driver an oval of
    ovality e turning at 150 rpm (sense -1: clockwise, the belt running against its order), a light
    driven pulley under 3 N m against it."""
    m = drivedyn.load(drivedyn.example_path("belt-5pk"))
    m = drivedyn.replace(m, {
        "simulation.model": "rotational", "simulation.duration": 1.0, "output.steady_window": [0.2, 1.0],
        "gravity": 0.0, "friction.law": law, "pulleys.driver.torque_time": None,
        "pulleys.driver.speed_time": [[0, 0], [0.1, sense * 150 * math.pi / 30]], "pulleys.driven.torque_speed": None,
        "pulleys.driven.torque": -3.0 * sense, "pulleys.driven.inertia": 0.002})
    if e is not None:
        m = drivedyn.replace(m, {"pulleys.driver.pitch_curve": {"kind": "oval", "ovality": e, "phase": 0.0}})
    return m


@pytest.mark.parametrize("law, sense", [("elastic-plastic", 1.0), ("threlfall", 1.0), ("elastic-plastic", -1.0),
                                         ("threlfall", -1.0)])
def test_a_smooth_oval_pulley_in_the_rotational_model(law, sense):
    """Friction belts on a turning curve (the wraps' cells carried past its two tangent points at their
    own rates; with Threlfall's law the steady content following the arc): ovality 0 reproduces the
    round drive within 1e-9; an oval driver of ovality 0.02 turns the driven pulley with a 2nd-order speed
    ratio within 3 % of the kinematic closed form (0.0200; 0.0203 / 0.0201 when written, the segment model
    0.0204, tests/belt/test_segment_curves.py), and the energy balance closes to 1e-2 of the work in."""
    a, b = drivedyn.run(_smooth_5pk(law, sense=sense)), drivedyn.run(_smooth_5pk(law, 0.0, sense))
    assert np.max(np.abs(a.ds["span_tension"].values - b.ds["span_tension"].values)) < 1e-9 * 600
    assert np.max(np.abs(a.ds["speed"].values - b.ds["speed"].values)) < 1e-9 * 150 * math.pi / 30
    res = drivedyn.run(_smooth_5pk(law, 0.02, sense))
    assert res.success, res.message
    ds = res.ds
    sel = ds["time"].values > 0.2
    th, om = ds["angle"].values[sel, 0], ds["speed"].values[sel]
    pred = []
    for t in np.linspace(0, math.pi, 91):
        lay = layout_at(["a", "b"], np.array([[0, 0], [0.515, 0]]), [Oval(0.027, 0.02, 0.0, 2), 0.027],
                        ["inside", "inside"], angles=np.array([t, 0.0]))
        pred.append((lay.spans[0].radius0 + lay.spans[1].radius1) / (2 * 0.027))
    amp = 0.5 * (max(pred) - min(pred))
    top = orders_of(th, om[:, 1] / om[:, 0])[0]
    assert top["order"] == 2.0 and top["amplitude"] == pytest.approx(amp, rel=0.03), (top, amp)
    assert res.summary["power"]["energy_residual_relative"] < 1e-2


def test_a_smooth_pitch_curve_with_friction_at_the_belts_centre_is_refused(tmp_path):
    m = drivedyn.replace(_smooth_5pk("threlfall", 0.02), {"friction.radius": "centre"})
    path = tmp_path / "smooth.toml"
    drivedyn.save(m, path)
    out = subprocess.run([sys.executable, "-m", "drivedyn", "run", str(path), "--no-plots", "--no-report",
                          "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert out.returncode == 2, out.stdout + out.stderr
    assert "friction.radius" in out.stderr and "Traceback" not in out.stderr


def test_a_smooth_crank_curve_of_ovality_0_beside_a_tensioner_reproduces_the_round_drive():
    """examples/fead-runup.toml's accessory drive (a clockwise crank with its orders, an automatic
    tensioner, a back-side idler) held at 3000 rpm, its crank pulley an oval of ovality 0: the tensioner's
    travel rolls belt on and off the curve's wrap as on the circle's, every number the round drive's."""
    m = drivedyn.load(drivedyn.example_path("fead-runup"))
    m = drivedyn.replace(m, {"simulation.model": "rotational", "simulation.duration": 0.4,
                             "output.steady_window": [0.2, 0.4],
                             "pulleys.crankshaft.speed_time": [[0, 0], [0.2, -3000 * math.pi / 30]]})
    a = drivedyn.run(m)
    b = drivedyn.run(drivedyn.replace(m, {"pulleys.crankshaft.pitch_curve": {"kind": "oval", "ovality": 0.0}}))
    assert np.max(np.abs(a.ds["span_tension"].values - b.ds["span_tension"].values)) < 1e-9 * 1000
    assert np.max(np.abs(a.ds["arm_angle"].values - b.ds["arm_angle"].values)) < 1e-9
