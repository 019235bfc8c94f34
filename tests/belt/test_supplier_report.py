"""The supplier's accessory-drive report (belt/supplier.py; geometry/catalogue.py, positions.py;
steady/duty.py, life.py) against three published Gates "Accessory Belt Drive System" reports: the
AG0868 drive with 8, 4 and 6 ribs (Gates program version 9.37), as transcribed in the MIT-licensed
repository kaydgn/MFSim, tests/fixtures/fead-validation.js at commit 3b9b07d3, entries
AG_MISC["AG0868"], AG_MISC["AG0868-4PK"], AG_MISC["AG0868-6PK"]. The numbers below are the reports'
printed values, copied as the fixture gives them; nobody tuned drivedyn to them.

Tolerances (what the issue asks and the reports' printed digits allow): tension and hub load within
0.5 % at every position-table row, angles within 0.2 deg, lengths within 0.2 mm (the reports print
0.1 mm and 0.1 deg); duty-row span tensions and hub loads (the supplier's fixed-arm convention)
within 1 %; B10 and the fatigue shares within the fit's stated error (steady/life.py).

Each report lists its pulleys against the belt's travel (the crank drives the span it lists first,
the tensioner sits on the span from the crank): the crank turns clockwise here.
"""
import math

import pytest

import drivedyn
from drivedyn.belt.geometry.drive import resolve
from drivedyn.belt.geometry.positions import ROWS, position_tables
from drivedyn.belt.steady.duty import duty_cycle
from drivedyn.belt.steady.life import belt_life

# pulley centres (mm) and the tensioner's drawn (mean) centre, pitch diameters (mm): the same drive in
# all three reports; pivot [195, 120] mm, arm 90 mm; the fixture's "order" CRK, A_C, TEN
PITCH = {"CRK": 177.41, "A_C": 120.41, "TEN": 77.2}
EFFECTIVE = {"CRK": 175.01, "A_C": 118.01, "TEN": 79.6}
DUTY = [(800, 27, 1.3), (1000, 10, 1.5), (1250, 13, 4.0), (1500, 18, 4.6), (1750, 19, 4.7), (2000, 13, 4.7)]

# per report: ribs, L (mm), tensioner centre (mm), free arm (deg), torque at the free arm (N m),
# rate (N m/deg), load stop (deg from the free arm); take-up (mm/deg), B10 (h), fatigue shares (%);
# the position table rows (rel, abs, X, Y, beta, dir, hub, T, wrap, EDL, REBL); duty tensions and hub
# loads (span leaving CRK, A_C, TEN in the report's order; hub loads CRK, A_C, TEN), N
REPORTS = {
    "8PK": dict(
        ribs=8, L=1020, ten=(126.06, 62.15), free=248, free_torque=8.56, rate=0.501, load=48.4,
        take_up=1.108, b10=24355, pulley_pct={"CRK": 2.7, "A_C": 25, "TEN": 72.4}, duty_pct=[16, 7, 13, 21, 25, 18],
        pos={"free arm": (0, 248, 161.3, 36.6, 33.2, 101.2, 173.9, 115.7, 97.4, 1051.5, 1051.8),
             "replace": (17, 231, 138.3, 50.1, 36, 87, 322.8, 268.2, 74, 1031.9, 1032.2),
             "max belt": (23.5, 224.5, 130.8, 56.9, 39.6, 84.1, 354.3, 318.8, 67.5, 1024.7, 1025),
             "mean": (28, 220, 126.1, 62.1, 42.7, 82.7, 370.1, 355.6, 62.7, 1019.7, 1020),
             "min belt": (32.5, 215.5, 121.7, 67.8, 46.3, 81.8, 381.9, 397.9, 57.4, 1014.7, 1015),
             "load stop": (48.4, 199.6, 110.2, 89.8, 62.9, 82.5, 409, 702.1, 33.9, 999.1, 999.4)},
        T=[(532, 357, 356), (518, 357, 356), (701, 356, 356), (686, 356, 356), (645, 356, 356), (609, 356, 356)],
        H=[(813, 882, 371), (801, 868, 371), (975, 1050, 371), (961, 1035, 370), (921, 994, 370), (887, 958, 370)]),
    "4PK": dict(
        ribs=4, L=1013, ten=(121.28, 68.38), free=230.1, free_torque=8.46, rate=0.505, load=24.1,
        take_up=1.087, b10=15894, pulley_pct={"CRK": 2.7, "A_C": 25, "TEN": 72.4}, duty_pct=[14, 6, 14, 23, 25, 18],
        pos={"free arm": (0, 230.1, 137.2, 51, 36.5, 86.5, 158.2, 132.8, 73.1, 1030.9, 1030.1),
             "replace": (4.1, 226, 132.5, 55.3, 38.7, 84.7, 187.2, 165.2, 69, 1026.3, 1025.6),
             "max belt": (10.5, 219.6, 125.6, 62.7, 43, 82.6, 224.4, 217.2, 62.2, 1019.2, 1018.4),
             "mean": (15.1, 215, 121.3, 68.4, 46.7, 81.7, 245.2, 257.8, 56.8, 1014.2, 1013.4),
             "min belt": (19.8, 210.3, 117.3, 74.6, 51.1, 81.4, 263.4, 308.6, 50.5, 1009.2, 1008.4),
             "load stop": (24.1, 206, 114.1, 80.6, 55.6, 81.6, 277.9, 370.4, 44.1, 1004.8, 1004)},
        T=[(434, 259, 258), (420, 259, 258), (603, 259, 258), (589, 258, 258), (547, 258, 258), (511, 258, 258)],
        H=[(640, 690, 246), (627, 676, 246), (803, 859, 246), (789, 844, 245), (749, 803, 245), (714, 767, 245)]),
    "6PK": dict(
        ribs=6, L=1018, ten=(124.57, 63.97), free=239.5, free_torque=8.65, rate=0.495, load=32.6,
        take_up=1.104, b10=21251, pulley_pct={"CRK": 2.7, "A_C": 25, "TEN": 72.4}, duty_pct=[15, 7, 14, 22, 25, 18],
        pos={"free arm": (0, 239.5, 149.3, 42.5, 32.9, 92.4, 176.7, 133, 83.3, 1041.4, 1041.4),
             "replace": (10.1, 229.4, 136.5, 51.6, 36.8, 86.2, 252.6, 213.7, 72.5, 1030.2, 1030.2),
             "max belt": (16.5, 223, 129.2, 58.6, 40.6, 83.6, 287.1, 263.8, 66, 1023, 1023),
             "mean": (21, 218.5, 124.6, 64, 43.8, 82.3, 305.3, 300.7, 61, 1018, 1018),
             "min belt": (25.6, 213.9, 120.3, 69.8, 47.6, 81.6, 320.3, 344.4, 55.4, 1013, 1013),
             "load stop": (32.6, 206.9, 114.7, 79.3, 54.6, 81.5, 337.8, 436.5, 45.5, 1005.7, 1005.7)},
        T=[(477, 302, 301), (463, 302, 301), (646, 302, 301), (632, 301, 301), (590, 301, 301), (554, 301, 301)],
        H=[(715, 774, 306), (702, 760, 306), (877, 942, 306), (863, 927, 306), (824, 886, 306), (789, 850, 306)]),
}


def _model(r, offset=None):
    rows = ",\n".join(f'{{crank_speed = "{rpm} rpm", share = "{pct} %", power = {{A_C = "{kw} kW"}}}}'
                      for rpm, pct, kw in DUTY)
    text = f'''
kind = "belt-drive"
[belt]
mass_per_length = 0.12
axial_stiffness = 1.2e5
pretension = "300 N"
profile = "PK"
ribs = {r["ribs"]}
effective_length = "{r["L"]} mm"
length_tolerance = "5 mm"
wear_allowance = "0.7 %"
{f'length_offset = "{offset} mm"' if offset is not None else ""}
[contact]
stiffness_linear = 2e9
[[pulleys]]
name = "CRK"
center = [0, 0]
radius = "{PITCH["CRK"] / 2} mm"
speed_time = [[0, "-800 rpm"], [1, "-800 rpm"]]
[[pulleys]]
name = "A_C"
center = ["263 mm", "15 mm"]
radius = "{PITCH["A_C"] / 2} mm"
[[pulleys]]
name = "TEN"
center = ["{r["ten"][0]} mm", "{r["ten"][1]} mm"]
radius = "{PITCH["TEN"] / 2} mm"
side = "back"
[pulleys.arm]
pivot = ["195 mm", "120 mm"]
inertia = 0.0009
rate = "{r["rate"]} N*m/deg"
free_angle = "{r["free"]} deg"
free_torque = "{r["free_torque"]} N*m"
load_stop = "{r["load"]} deg"
[duty_cycle]
temperature = 90
rows = [{rows}]
'''
    return drivedyn.loads(text)


@pytest.mark.parametrize("name", list(REPORTS))
def test_position_table_row_by_row(name):
    r = REPORTS[name]
    printed_offset = r["pos"]["mean"][9] - r["pos"]["mean"][10]      # the report's EDL - REBL
    table = position_tables(resolve(_model(r, offset=printed_offset)))[0]
    assert not table.unreached
    deg = math.degrees
    for row_name, got in zip(ROWS, table.rows):
        rel, ab, X, Y, beta, direction, hub, T, wrap, edl, rebl = r["pos"][row_name]
        where = f"{name} {row_name}"
        # rel and abs are printed to 0.1 deg (the replace row's to 1 deg)
        tol_deg = 0.6 if row_name == "replace" else 0.2
        assert deg(got.rel) == pytest.approx(rel, abs=tol_deg), where
        assert deg(got.angle) % 360 == pytest.approx(ab, abs=tol_deg), where
        assert got.centre[0] * 1e3 == pytest.approx(X, abs=0.2) and got.centre[1] * 1e3 == pytest.approx(Y, abs=0.2), where
        assert deg(got.beta) == pytest.approx(beta, abs=0.6 if row_name == "replace" else 0.2), where
        assert deg(got.hub_direction) % 360 == pytest.approx(direction, abs=0.6 if row_name == "replace" else 0.2), where
        assert deg(got.wrap) == pytest.approx(wrap, abs=0.6 if row_name == "replace" else 0.2), where
        assert got.edl * 1e3 == pytest.approx(edl, abs=0.2) and got.rebl * 1e3 == pytest.approx(rebl, abs=0.2), where
        assert got.tension == pytest.approx(T, rel=5e-3), where
        assert got.hub_load == pytest.approx(hub, rel=5e-3), where
    # the take-up ratio d(EDL)/d(arm angle) at the mean position, printed to 1 um/deg
    assert table.take_up * 1e3 * math.pi / 180 == pytest.approx(r["take_up"], abs=1.5e-3)


@pytest.mark.parametrize("name", list(REPORTS))
def test_duty_cycle_in_the_suppliers_convention(name):
    """Span tensions and hub loads per duty row with the arm fixed (the span from the crank into the
    tensioner held at the design tension; Gates adds 0.01 kW of drag on the tensioner)."""
    r = REPORTS[name]
    drive = resolve(_model(r))
    design = position_tables(drive)[0].design_tension
    for k, row in enumerate(duty_cycle(drive, design)):
        fa = row.fixed_arm
        T = (fa.spans["CRK-A_C"], fa.spans["A_C-TEN"], fa.spans["TEN-CRK"])
        H = (fa.hub_load["CRK"], fa.hub_load["A_C"], fa.hub_load["TEN"])
        for got, want in zip(T + H, r["T"][k] + r["H"][k]):
            assert got == pytest.approx(want, rel=0.01), (name, DUTY[k][0], got, want)


@pytest.mark.parametrize("name", list(REPORTS))
def test_belt_life_and_fatigue_shares_within_the_fits_error(name):
    """B10 within the fit's 2.4 % RMS (5 % here: about twice it); the pulleys' shares of the
    rib-fatigue damage within 1.5 points (the reports print whole per cent). The fit weights the
    duty rows by share x belt speed only, the supplier also by their loads: measured on these three
    reports the rows' shares are off by up to 1.4 (8PK), 2.9 (4PK) and 1.9 (6PK) points, which the
    test holds (3 points): a tighter row share needs the supplier's load weighting, not published."""
    r = REPORTS[name]
    model = _model(r)
    drive = resolve(model)
    design = position_tables(drive)[0].design_tension
    rows = duty_cycle(drive, design)
    life = belt_life(model, design, [x.belt_speed for x in rows])
    assert life.in_range
    assert life.b10_hours == pytest.approx(r["b10"], rel=0.05)
    for n, pct in r["pulley_pct"].items():
        assert 100 * life.pulley_share[n] == pytest.approx(pct, abs=1.5), n
    for got, pct in zip(life.row_share, r["duty_pct"]):
        assert 100 * got == pytest.approx(pct, abs=3.0)


def test_effective_diameters_and_the_check_report():
    """PK's effective diameters (grooved d_p - 2.4 mm, back side d_p + 2.4 mm) as printed, and the
    report's tables in check (text and --json)."""
    model = _model(REPORTS["8PK"])
    data = drivedyn.core.analyses.analysis("belt-drive").check_data(model)["supplier"]
    for n, d in EFFECTIVE.items():
        assert data["pulleys"][n]["effective_diameter"] * 1e3 == pytest.approx(d, abs=1e-9)
    assert set(data) >= {"belt", "pulleys", "positions", "duty", "life"}
    text = drivedyn.check(model)
    for what in ("position table", "mean", "load stop", "belt take-up 1.108 mm/deg", "duty cycle", "belt life B10"):
        assert what in text


def test_running_balance_against_an_independent_length_kept_calculation():
    """The running-arm columns keep the belt's installed length: the unstretched belt the running
    spans hold (each span's length / (1 + T / EA) plus the wraps') equals the installed length, and
    the arm's spring balances the hub force of T - m v^2 (checked here by virtual work, written out)."""
    import numpy as np

    from drivedyn.belt.geometry import tensioner as TN
    from drivedyn.mechanics.layout import compute_layout

    model = _model(REPORTS["8PK"])
    drive = resolve(model)
    rows = duty_cycle(drive, position_tables(drive)[0].design_tension)
    EA, m = model.belt.axial_stiffness, model.belt.mass_per_length
    rest = drive.equilibrium
    # installed, continuum: the rest path less the belt sunk into each wrap by its pressure T / r
    # (contact law c2 p = T / r), counted at the rest tension as the running belt is counted below
    lay_rest = compute_layout(rest.model)
    sunk_rest = sum(lay_rest.wrap[k] * (rest.tension / abs(lay_rest.rho[k])) / model.contact.stiffness_linear
                    for k in range(len(lay_rest.names)))
    L_rest = (lay_rest.length - sunk_rest) / (1 + rest.tension / EA)
    for row in rows:
        assert row.running_arm is not None, row.note
        q = row.arm_travel["TEN"]
        j, s = drive.tensioners[0], drive.senses[0]
        lay = compute_layout(TN.with_centres(model, {j: TN.centre(model, j, q, s)}))
        T = np.array([row.running_arm.spans[sp.name] for sp in lay.spans])
        # the belt on the spans and wraps at running tensions; on a wrap (classical creep theory,
        # Grashof / Johnson): the entry span's tension over the adhesion arc, then e^(mu psi) in
        # T - m v^2 over the slip arc to the exit span's. The belt travels against the listed order
        # here (crank clockwise): pulley k's entry span is span k, its exit span k - 1
        c = m * row.belt_speed ** 2
        mu = model.friction.coefficient
        held = sum(sp.length / (1 + t / EA) for sp, t in zip(lay.spans, T))
        nk = len(lay.names)
        for k in range(nk):
            te, tx = T[k], T[(k - 1) % nk]
            slip = abs(math.log((tx - c) / (te - c))) / mu
            psi = np.linspace(0.0, slip, 2001)
            tt = c + (te - c) * np.exp(np.sign(tx - te) * mu * psi)
            arc = np.trapezoid(1 / (1 + tt / EA), psi) if slip > 0 else 0.0
            held += abs(lay.rho[k]) * ((lay.wrap[k] - slip) / (1 + te / EA) + arc)
            # the belt sunk into the groove by its pressure T / r (contact law c2 p = T / r): its
            # centre line runs p inside the pitch circle over the wrap
            held -= lay.wrap[k] * (0.5 * (te + tx) / abs(lay.rho[k])) / model.contact.stiffness_linear
        assert held == pytest.approx(L_rest, abs=5e-6)
        hub = np.zeros(2)
        for sp, t in zip(lay.spans, T):
            u = np.array([math.cos(sp.angle), math.sin(sp.angle)])
            hub += (t - c) * u * ((sp.start == j) - (sp.end == j))
        h = 1e-6
        dc = (np.array(TN.centre(model, j, q + h, s)) - np.array(TN.centre(model, j, q - h, s))) / (2 * h)
        spring = TN.spring_load(model.pulleys[j].arm, q)
        assert spring + hub @ dc == pytest.approx(0.0, abs=1e-3 * spring)


def test_running_balance_against_the_segment_model_at_the_first_duty_row():
    """examples/fead-ag0868.toml runs its first duty row (800 rpm, 1.3 kW on the A/C) with the segment
    model, the arm free: its mean span tensions and hub loads agree with the running-arm columns of
    the duty cycle (creep theory, belt length kept, the arm without friction) within 0.8 % once the
    arm's Coulomb friction is taken out (with the example's 1 N m against a 22.6 N m spring the arm
    may rest anywhere in a band of about +-4 % of the tension, and did 1.0 % off)."""
    model = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-ag0868")), {"pulleys.2.arm.friction": 0.0})
    r = drivedyn.run(model)
    assert r.status == "success", [d.line() for d in r.diagnostics]
    s = r.summary
    row = s["supplier"]["duty"]["rows"][0]
    assert row["running_arm"] is not None
    for sp, t in row["running_arm"]["spans"].items():
        assert s["spans"][sp]["tension_mean"] == pytest.approx(t, rel=0.008), sp
    for n, h in row["running_arm"]["hub_load"].items():
        assert s["pulleys"][n]["hub_load"] == pytest.approx(h, rel=0.008), n
    assert s["verdict"] == "pass"
    names = {c for c in s["criteria"]}
    assert {"duty_slip_factor", "duty_rows_carried", "duty_stop_clearance", "belt_life"} <= names


def test_slip_factor_under_the_cranks_acceleration():
    """The A/C's slip safety factor under +-1000 rpm/s of the crank, written out: its torque is the
    load (10 % of its largest duty power, at its speed) plus its inertia's J alpha, alpha the crank's
    times the speed ratio; with the arm fixed the span leaving it into the tensioner holds the design
    tension plus the tensioner's drag, so its capacity is (T_slack - m v^2)(e^(mu phi) - 1) r."""
    from drivedyn.belt.steady.duty import acceleration_envelope

    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    drive = resolve(model)
    design = position_tables(drive)[0].design_tension
    env = acceleration_envelope(drive, design)
    lay = drive.layout
    r_c, r_a = PITCH["CRK"] / 2e3, PITCH["A_C"] / 2e3
    j = [p.name for p in model.pulleys].index("A_C")
    dc = model.duty_cycle
    for e in env:
        v = e["crank_speed"] * r_c
        w_a = v / r_a
        alpha = dc.acceleration * r_c / r_a
        # the span from the tensioner into the A/C: the design tension, the tensioner's drag and its
        # pulley's inertia torque J alpha over its radius (speeding up pulls it, slowing down pushes)
        r_t, J_t = PITCH["TEN"] / 2e3, model.pulleys[2].inertia
        a_t = dc.acceleration * r_c / r_t
        slack_acc = design + dc.idler_drag / v + J_t * a_t / r_t - model.belt.mass_per_length * v * v
        slack_dec = design + dc.idler_drag / v - J_t * a_t / r_t - model.belt.mass_per_length * v * v
        grip = math.expm1(model.friction.coefficient * lay.wrap[j]) * r_a
        load = 0.1 * 4.7e3 / w_a
        J = model.pulleys[j].inertia
        acc, dec = e["part_load_accelerating"], e["part_load_decelerating"]
        assert acc["factors"]["A_C"] == pytest.approx(slack_acc * grip / (load + J * alpha), rel=1e-3)
        assert dec["factors"]["A_C"] == pytest.approx(slack_dec * grip / abs(load - J * alpha), rel=1e-3)
        assert acc["slip_factor"] == min(acc["factors"].values())


def test_entry_angles_from_offset_and_misalignment():
    """A 500 mm span between two pulleys: an axial offset of 2 mm enters at atan(2 / L_span); a pulley
    turned by 0.5 deg about the direction across the span tilts its groove against it by the whole
    0.5 deg, about the span's own direction by nothing (first order)."""
    from drivedyn.belt.geometry.alignment import entry_angles
    from drivedyn.mechanics.layout import compute_layout

    base = '''
kind = "belt-drive"
[belt]
mass_per_length = 0.1
axial_stiffness = 1e5
pretension = 300
[contact]
stiffness_linear = 1e9
[[pulleys]]
name = "a"
center = [0, 0]
radius = 0.05
[[pulleys]]
name = "b"
center = [0.5, 0]
radius = 0.05
'''
    m = drivedyn.loads(base.replace('radius = 0.05\n[[pulleys]]', 'radius = 0.05\naxial_offset = "2 mm"\n[[pulleys]]', 1))
    lay = compute_layout(m)
    a = entry_angles(m, lay)
    L = lay.spans[0].length
    assert a["b"]["arriving"] == pytest.approx(math.atan(2e-3 / L), rel=1e-9)
    assert a["a"]["leaving"] == pytest.approx(math.atan(2e-3 / L), rel=1e-9)
    across = drivedyn.loads(base + 'misalignment = "0.5 deg"\nmisalignment_axis = "90 deg"\n')
    along = drivedyn.loads(base + 'misalignment = "0.5 deg"\nmisalignment_axis = "0 deg"\n')
    assert math.degrees(entry_angles(across, compute_layout(across))["b"]["arriving"]) == pytest.approx(0.5, rel=1e-9)
    assert math.degrees(entry_angles(along, compute_layout(along))["b"]["arriving"]) == pytest.approx(0.0, abs=1e-12)
    data = drivedyn.core.analyses.analysis("belt-drive").check_data(across)["supplier"]
    assert data["alignment"]["entry_angles"]["b"]["arriving"] == pytest.approx(math.radians(0.5))


def test_tolerance_study_rows():
    """The tolerance study's mean row is the duty cycle itself; a longer (worn) belt carries less
    tension, so its hub loads are lower and its running slip factor smaller, row by row."""
    from drivedyn.belt.supplier import report_data

    data = report_data(resolve(drivedyn.load(drivedyn.example_path("fead-ag0868"))))
    tol = {e["position"]: e for e in data["tolerance"]}
    assert list(tol) == ["replace", "max belt", "mean", "min belt"]
    rows = data["duty"]["rows"]
    mean = tol["mean"]
    assert mean["slip_factor_fixed"] == pytest.approx(min(v for r in rows for v in r["fixed_arm"]["slip_factor"].values()
                                                          if v is not None), rel=1e-6)
    for n in mean["hub_load_fixed"]:
        assert mean["hub_load_fixed"][n] == pytest.approx(max(r["fixed_arm"]["hub_load"][n] for r in rows), rel=1e-6)
    order = ["replace", "max belt", "mean", "min belt"]
    for a, b in zip(order, order[1:]):
        assert tol[a]["tension"] < tol[b]["tension"]
        assert tol[a]["slip_factor_running"] < tol[b]["slip_factor_running"]
        assert all(tol[a]["hub_load_running"][n] < tol[b]["hub_load_running"][n] for n in mean["hub_load_running"])


@pytest.mark.parametrize("change, words", [
    ({"pulleys.2.arm.free_angle": math.radians(190)}, "slackens the belt"),
    ({"pulleys.2.arm.load_stop": math.radians(20)}, "lies before the drawn arm"),
    ({"belt.length_tolerance": 0.04}, "does not cover the belt's tolerance"),
])
def test_inconsistent_tensioner_data_is_one_line_naming_the_field(change, words):
    """A free arm on the belt's slack side, a load stop before the drawn (mean) arm, a tolerance band
    the arm's travel cannot cover: one line that names the field and the numbers, no report."""
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    with pytest.raises(drivedyn.ModelError) as info:
        drivedyn.check(drivedyn.replace(model, change))
    text = str(info.value)
    assert words in text and "\n" not in text and ("pulleys" in text or "belt" in text)


def test_supplier_tensioner_data_varied_alone():
    """A design loop varies the supplier's data alone (drivedyn.replace writes the derived preload and
    stops back): the preload and stops follow the new data."""
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    arm = model.pulleys[2].arm
    stiffer = drivedyn.replace(model, {"pulleys.2.arm.free_torque": arm.free_torque + 1.0})
    assert stiffer.pulleys[2].arm.preload == pytest.approx(arm.preload + 1.0)
    later = drivedyn.replace(model, {"pulleys.2.arm.load_stop": arm.load_stop + 0.1})
    assert later.pulleys[2].arm.stops[0] == pytest.approx(arm.stops[0] - 0.1)
    assert drivedyn.loads(drivedyn.dumps(model)) == model
