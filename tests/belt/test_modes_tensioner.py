"""Rotational modes of a drive with a tensioner arm, against references written here:

- the arm's static balance by virtual work on the continuum belt (the spring's torque against the
  tension times d(path length)/d(arm angle), the tension from the installed length);
- the modes of the massless-belt drive from the Hessian of the span energies, each span a bar
  between material points that the pulleys carry (belt stuck to the wraps), by finite differences
  of the total energy, with the inertias on the diagonal;
- a free-response run of the dynamic segment model with the real belt mass (within 3 %);
- a span's stretch per unit tensioner travel: the projection of the centre's motion on the span.

Drive: crank held (75 mm), back-side tensioner on an arm pushing into the span between crank and
alternator (35 mm, arm 70 mm), alternator (28 mm); belt 0.1 kg/m, EA 1.5e5 N, 300 N at the drawn
position.
"""
import math

import numpy as np
import pytest
from scipy.linalg import eigh
from scipy.optimize import brentq

import drivedyn
from drivedyn.mechanics.layout import compute_layout
from drivedyn.belt.steady.modes import _stretch_derivatives, drive_linear_model, drive_modes, modes
from drivedyn.belt.geometry.tensioner import equilibrium, with_centres
from drivedyn.core.model import from_dict, to_dict


def drive(mass=0.1, segments=200, duration=0.5):
    return from_dict({
        "kind": "belt-drive", "name": "three pulleys, tensioner arm",
        "belt": {"mass_per_length": mass, "axial_stiffness": 1.5e5, "axial_damping": 0.0, "pretension": 300.0,
                 "segments": segments, "bending_stiffness": 2e-4},
        "contact": {"stiffness_linear": 8e7, "stiffness_quadratic": 4e11, "damping": 3e4},
        "friction": {"law": "threlfall", "coefficient": 1.0, "velocity_threshold": 1e-5},    # adhesion, as the Hessian here
        "simulation": {"duration": duration}, "output": {"interval": 1e-4, "frames": 2},
        "pulleys": [
            {"name": "crank", "center": [0, 0], "radius": 0.075, "speed_time": [[0, 0], [1, 0]]},
            {"name": "tensioner", "center": [0.15, -0.01], "radius": 0.035, "side": "back", "inertia": 1e-4,
             "arm": {"pivot": [0.22, -0.01], "inertia": 2e-3, "preload": 16.0, "rate": 30.0}},
            {"name": "alternator", "center": [0.30, 0.05], "radius": 0.028, "inertia": 2e-4}]})


def _rot(a, v):
    return np.array([math.cos(a) * v[0] - math.sin(a) * v[1], math.sin(a) * v[0] + math.cos(a) * v[1]])


def _virtual_work_balance(m):
    """Arm angle increment q (ccw, from the drawn position) and tension of the continuum belt."""
    arm, EA = m.pulleys[1].arm, m.belt.axial_stiffness
    c0, piv = np.array(m.pulleys[1].center), np.array(arm.pivot)
    centre = lambda q: piv + _rot(q, c0 - piv)
    path = lambda q: compute_layout(with_centres(m, {1: tuple(centre(q))})).length
    L0 = path(0.0) / (1 + m.belt.pretension / EA)          # installed length: the pretension at the drawn position
    s = 1.0 if path(1e-4) > path(-1e-4) else -1.0         # ccw sense that pushes into the belt
    h = 1e-6
    work = lambda q: s * (arm.preload - arm.rate * s * q) - EA * (path(q) / L0 - 1) * (path(q + h) - path(q - h)) / (2 * h)
    q = brentq(work, -0.3, 0.3, xtol=1e-13)
    return q, EA * (path(q) / L0 - 1), s


def test_arm_balance_by_virtual_work():
    m = drive()
    q, T, s = _virtual_work_balance(m)
    rest = equilibrium(m)
    assert rest.tension == pytest.approx(T, rel=5e-3)
    # the arm's angle to 0.05 degrees (its travel is a few milliradians)
    assert abs(s * q - rest.travel[0]) < math.radians(0.05)


def _energy_hessian_modes(m, q_abs, T):
    """Modes (Hz) of the massless-belt drive about the arm at q_abs with tension T: each span a bar
    between material points carried by its pulleys; DOFs tensioner turn, alternator turn, arm."""
    arm, EA = m.pulleys[1].arm, m.belt.axial_stiffness
    piv, c0 = np.array(arm.pivot), np.array(m.pulleys[1].center)
    cq = piv + _rot(q_abs, c0 - piv)
    lay = compute_layout(with_centres(m, {1: tuple(cq)}))
    L0 = [sp.length / (1 + T / EA) for sp in lay.spans]

    def pos(x, j, pt):
        c = lay.centers[j]
        turn = {0: 0.0, 1: x[0], 2: x[1]}[j]
        centre = c if j != 1 else piv + _rot(x[2], cq - piv)
        return centre + _rot(turn, np.asarray(pt) - c)

    s = 1.0 if compute_layout(with_centres(m, {1: tuple(piv + _rot(q_abs + 1e-4, c0 - piv))})).length > lay.length else -1.0

    def energy(x):
        e = sum(EA / (2 * L0[k]) * (np.linalg.norm(pos(x, sp.end, sp.p1) - pos(x, sp.start, sp.p0)) - L0[k]) ** 2
                for k, sp in enumerate(lay.spans))
        # the spring's work: torque s (preload - rate travel), travel into the belt s q
        return e - s * (arm.preload * x[2] - arm.rate * s * (q_abs * x[2] + x[2] ** 2 / 2))

    h, n = 1e-6, 3
    H = np.zeros((n, n))
    for a in range(n):
        for b in range(n):
            ea, eb = np.eye(n)[a] * h, np.eye(n)[b] * h
            H[a, b] = (energy(ea + eb) - energy(ea - eb) - energy(eb - ea) + energy(-ea - eb)) / (4 * h * h)
    M = np.diag([m.pulleys[1].inertia, m.pulleys[2].inertia, arm.inertia])
    return np.sqrt(eigh(H, M, eigvals_only=True)) / (2 * math.pi)


def test_modes_against_the_span_energy_hessian():
    m = drive(mass=1e-9)
    rest = equilibrium(m)
    s = _virtual_work_balance(m)[2]
    ref = _energy_hessian_modes(m, s * rest.travel[0], rest.tension)
    got = drive_modes(m).frequencies_hz
    assert len(got) == 3
    np.testing.assert_allclose(got, ref, rtol=5e-3)


def test_stretch_per_travel_is_the_projection_of_the_centre_motion():
    m = drive()
    lay = compute_layout(m)
    g, _ = _stretch_derivatives(m, lay, [1])
    arm = m.pulleys[1].arm
    r = np.array(m.pulleys[1].center) - np.array(arm.pivot)
    dc = np.array([-r[1], r[0]])                      # centre velocity per unit ccw arm turn
    for k, sp in enumerate(lay.spans):
        u = np.subtract(sp.p1, sp.p0) / sp.length
        want = -u @ dc if sp.start == 1 else (u @ dc if sp.end == 1 else 0.0)
        assert g[k, 0] == pytest.approx(want, rel=1e-5, abs=1e-9)
    # and it is not the change of the straight span length (what belt sliding round the pulleys would give)
    straight = [(compute_layout(with_centres(m, {1: tuple(np.array(m.pulleys[1].center) + 1e-6 * dc)})).spans[k].length
                 - sp.length) / 1e-6 for k, sp in enumerate(lay.spans)]
    assert abs(straight[0] - g[0, 0]) > 0.05 * abs(g[0, 0])


def test_one_way_clutch_rotor_locked_and_free():
    d = to_dict(drive())
    d["pulleys"][2]["clutch"] = {"type": "one-way", "inertia": 3e-3}
    md = modes(from_dict(d))
    locked, free = to_dict(drive()), to_dict(drive())
    locked["pulleys"][2]["inertia"] = 2e-4 + 3e-3
    np.testing.assert_allclose(md.frequencies_hz, modes(from_dict(locked)).frequencies_hz, rtol=1e-9)
    np.testing.assert_allclose(md.free_rotor_hz, modes(from_dict(free)).frequencies_hz, rtol=1e-9)
    assert md.frequencies_hz[0] < 0.8 * md.free_rotor_hz[0]          # the rotor's inertia lowers the first mode


def _peak_near(t, x, f0):
    x = x - x.mean()
    nfft = 16 * len(x)
    X = np.abs(np.fft.rfft(x * np.hanning(len(x)), nfft))
    f = np.fft.rfftfreq(nfft, t[1] - t[0])
    w = (f > 0.85 * f0) & (f < 1.15 * f0)
    return float(f[w][np.argmax(X[w])])


def _free_response(law):
    """Torque pulses on the alternator and the tensioner pulley, then free vibration for 1 s (100 us
    samples): the model and, per mode of ``drive_modes``, the relative distance to the nearest peak
    of the response (the DOF that moves most in a mode shows it best)."""
    d = to_dict(drive(mass=0.1, segments=200, duration=1.0))
    d["pulleys"][1]["torque_time"] = [[0, 0], [0.002, 2.0], [0.004, 0.0], [1.0, 0.0]]
    d["pulleys"][2]["torque_time"] = [[0, 0], [0.001, 0.5], [0.002, 0.0], [1.0, 0.0]]
    d["output"]["steady_window"] = [0.01, 1.0]
    d["friction"]["law"] = law
    m = from_dict(d)
    r = drivedyn.run(m)
    t = r.ds["time"].values
    sel = t > 0.01
    md = drive_modes(m)
    off = []
    for f0 in md.frequencies_hz:
        got = [_peak_near(t[sel], r.ds["speed"].sel(pulley=p).values[sel], f0) for p in ("alternator", "tensioner")]
        got.append(_peak_near(t[sel], r.ds["arm_travel"].values[sel, 0], f0))
        off.append(min(abs(g / f0 - 1) for g in got))
    return m, md, off


@pytest.mark.slow
def test_modes_against_a_free_response_of_the_segment_model():
    """Each mode's peak in the free response within 3 % of the linear model with the belt's mass."""
    _, md, off = _free_response("threlfall")
    for f0, e in zip(md.frequencies_hz, off):
        assert e < 0.03, (f0, e)


@pytest.mark.slow
def test_modes_with_the_wraps_pre_sliding_compliance():
    """The same free response with the elastic-plastic friction law: each stuck bit of belt is held
    by a bristle (mu N / Delta_max), so the wraps give, and the modes fall 13-36 % below the
    adhesion model's (measured 86.2 / 326.2 / 861.6 Hz). The modes with the wraps' shear lag, the
    belt's sinking into the rims included (modes._wrap_compliance), against the response, measured:
    72.02 / 257.87 / 541.69 Hz, 0.1 / 1.2 / 1.0 % from its peaks (without the sinking 75.06 / 268.18
    / 555.59 Hz, 3.9 / 2.7 / 1.1 %). With Threlfall's law the adhesion model is 1.5 / 1.6 / 2.1 %
    above the response (85.0 / 320.9 / 843.9 Hz)."""
    m, md, off = _free_response("elastic-plastic")
    adhesion = drive_modes(drivedyn.replace(m, {"friction.law": "threlfall"}))
    for f0, fa, e in zip(md.frequencies_hz, adhesion.frequencies_hz, off):
        assert f0 < 0.9 * fa
        assert e < 0.03, (f0, e)


@pytest.mark.slow
def test_static_compliance_of_the_wraps():
    """A torque of 0.5 N m held on the alternator (crank held) turns the segment model's pulleys and
    arm as the linear model's stiffness says (K x = f), the wraps' bristles and the belt's sinking
    into the rims included: measured within 0.13 / 0.22 / 0.40 % (alternator, tensioner pulley,
    arm) at Delta_max 0.1 mm, where the shear lag of the belt's own EA alone is 5.8-6.6 % too stiff.
    The rotational model, whose wraps carry the same lags, turns within 0.2 / 0.35 / 0.46 % of the
    segment model (its wraps with the belt's own EA: 6 % less). A static load separates the
    stiffness from the masses, which the free response mixes."""
    d = to_dict(drive(mass=0.1, segments=200, duration=0.6))
    d["friction"]["law"] = "elastic-plastic"
    d["pulleys"][2]["torque_time"] = [[0, 0], [0.3, 0.5], [1.0, 0.5]]
    d["belt"]["axial_damping"] = 20.0                 # settles the ramp's ringing
    d["output"]["steady_window"] = [0.4, 0.6]
    m = from_dict(d)
    lm = drive_linear_model(m)
    f = np.zeros(len(lm.dofs))
    f[lm.dofs.index("alternator")] = 0.5
    want = np.linalg.solve(lm.K, f)

    def turned(r):
        """Alternator and tensioner pulley turns, and the arm's travel (measured into the belt; the
        linear model's DOF turns counter-clockwise: compared in magnitude), over the held load."""
        sel = r.ds["time"].values > 0.45
        out = []
        for p in ("alternator", "tensioner"):
            th = r.ds["angle"].sel(pulley=p).values
            out.append(th[sel].mean() - th[0])
        arm = r.ds["arm_travel"].values[:, 0]
        return np.array(out + [abs(arm[sel].mean() - arm[0])])

    seg = turned(drivedyn.run(m))
    lin = np.array([want[lm.dofs.index("alternator")], want[lm.dofs.index("tensioner")],
                    abs(want[lm.dofs.index("tensioner.arm")])])
    np.testing.assert_allclose(seg, lin, rtol=0.01)
    rot = turned(drivedyn.run(drivedyn.replace(m, {"simulation.model": "rotational"})))
    np.testing.assert_allclose(rot, seg, rtol=0.01)
