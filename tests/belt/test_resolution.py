"""The belt's resolution at the defaults (belt.segments = "auto"), against references written here:
the slip of every pulley of a six-pulley accessory drive running steady against creep theory
(steady/creep.py: each pulley's speed ratio (EA + T_in) / (EA + T_in,driver) of its span tensions), and
the rule's pick and what the summary reports of it."""
import math

import pytest

import drivedyn
from drivedyn.belt.geometry.segment_count import SAG_RATIO, SAG_RATIO_PRESLIDING, WRAP_SEGMENTS, auto_segments, sag_ratio
from drivedyn.belt.steady.creep import steady_state
from drivedyn.core.model import from_dict, to_dict


def held(rpm, segments="auto", duration=0.8):
    """examples/fead-runup.toml with its crank held at rpm (ramped over 0.3 s), no orders or harmonics."""
    d = to_dict(drivedyn.load(drivedyn.example_path("fead-runup")))
    w = -rpm * math.pi / 30
    d["pulleys"][0]["speed_time"] = [[0.0, 0.0], [0.3, w], [duration, w]]
    d["pulleys"][0].pop("speed_orders", None)
    for p in d["pulleys"]:
        p.pop("harmonics", None)
    d["belt"]["segments"] = segments
    d["simulation"]["duration"] = duration
    d["output"].update(runup_bin=None, steady_window=[duration - 0.2, duration])
    return from_dict(d)


def test_auto_resolves_the_shortest_wrap_and_the_chordal_landing():
    """The chord sag l^2 / (8 r) against the contact depth at the pretension's pressure T0 / r,
    written out here for the 28 mm alternator (c1 p^2 + c2 p = T0 / r, the example's 6PK contact),
    sets the count on this drive with Threlfall's law; the 45 degree tensioner wrap then holds more
    than six."""
    m = drivedyn.replace(held(3000), {"friction.law": "threlfall"})
    n, why = auto_segments(m)
    assert "chord sag" in why and "alternator" in why
    from drivedyn.mechanics.layout import compute_layout

    lay = compute_layout(m)
    l = lay.length / n
    T0, r, c1, c2 = 350.0, 0.028, 4.54e11, 9.75e7
    p = (-c2 + math.sqrt(c2 * c2 + 4 * c1 * T0 / r)) / (2 * c1)
    assert l * l / (8 * r * p) == pytest.approx(SAG_RATIO, rel=0.01)
    assert 35e-3 * math.radians(45) / l >= WRAP_SEGMENTS
    assert 640 < n < 700


@pytest.mark.slow
def test_elastic_plastic_friction_converges_at_a_coarser_sag():
    """With the elastic-plastic law "auto" allows a chord sag of SAG_RATIO_PRESLIDING x the depth
    (half the segments): the drive held at 3000 rpm with its orders agrees with twice the segments
    (span bands within 3 %, slips within 0.03 points; measured with the implicit scheme, the
    default: minima within 2.3 %, maxima 0.5 %, slips 0.005 points, and within 1.6 % / 0.9 % /
    0.005 of 1332 segments: docs/belt-drive.md). The losses, 132.4 W against 109.4 W, are 23 %
    discretisation by their l^2 extrapolation, within the stated 30 %."""
    from bench_fead_convergence import held as with_orders

    m = drivedyn.replace(with_orders(3000, "auto"), {"friction.law": "elastic-plastic"})
    n, why = auto_segments(m)
    assert f"{SAG_RATIO_PRESLIDING:g} x the contact depth" in why
    threlfall = drivedyn.replace(with_orders(3000, "auto"), {"friction.law": "threlfall"})
    assert abs(n - auto_segments(threlfall)[0] * math.sqrt(SAG_RATIO / SAG_RATIO_PRESLIDING)) <= 1
    a = drivedyn.run(m).summary
    b = drivedyn.run(drivedyn.replace(m, {"belt.segments": 2 * n})).summary
    for sp, v in a["spans"].items():
        for k in ("tension_min", "tension_max"):
            assert v[k] == pytest.approx(b["spans"][sp][k], rel=0.03), (sp, k)
    for p, v in a["pulleys"].items():
        assert v["slip"] == pytest.approx(b["pulleys"][p]["slip"], abs=3e-4), p
    # the error the run states without a resolution check (the rule's accuracy) covers the change
    e = a["discretisation"]["estimate"]
    assert e["auto_segments"] == n and "fead-runup" in e["method"]
    for sp, v in a["spans"].items():
        for k in ("tension_min", "tension_max"):
            assert abs(v[k] / b["spans"][sp][k] - 1) <= e["tension_relative_largest"], (sp, k)
    for p, v in a["pulleys"].items():
        assert abs(v["slip"] - b["pulleys"][p]["slip"]) <= e["slip_largest"], p
    # and the losses' share that is discretisation: the losses less their l^2 limit from the pair
    la, lb = sum(a["power"]["losses"].values()), sum(b["power"]["losses"].values())
    assert lb < la and (la - (lb - (la - lb) / 3)) / la <= e["power_loss_relative"]


@pytest.mark.slow
def test_slip_at_the_defaults_against_creep_theory():
    """3000 rpm (23.6 m/s), the alternator at 8000 rpm: every pulley's mean slip within 0.03
    percentage points of steady creep theory (measured at the defaults, the elastic-plastic law and
    333 segments: compressor 0.076 / idler 0.071 / pump 0.083 / alternator 0.105 / tensioner 0.095 %
    against 0.055 / 0.055 / 0.061 / 0.081 / 0.082: the bristles' own creep, 0.013-0.024 points; with
    Threlfall's law at 300 segments 0.050 / 0.032 / 0.079 / 0.079 / 0.078; 150 segments without the
    rolling-radius correction read 0.13-0.93 %)."""
    m = held(3000)
    r = drivedyn.run(m)
    st = steady_state(m)
    for name, p in r.summary["pulleys"].items():
        if name == "crankshaft":
            continue
        want = 1 - abs(st.pulleys[name].speed_ratio)
        assert p["slip"] == pytest.approx(want, abs=3e-4), (name, p["slip"], want)
    d = r.summary["discretisation"]
    assert d["segments"] == auto_segments(m)[0] and d["shortest_wrap"] == "tensioner"
    assert d["segments_on_shortest_wrap"] >= 0.97 * WRAP_SEGMENTS
    assert d["chord_sag_to_depth"] <= sag_ratio(m)
    assert "coarse-discretisation" not in [x.code for x in r.diagnostics]


def test_a_wrap_with_too_few_segments_is_reported():
    r = drivedyn.run(held(3000, segments=150, duration=0.35))
    codes = {x.code: x for x in r.diagnostics}
    assert "coarse-discretisation" in codes
    assert "tensioner" in codes["coarse-discretisation"].text
    assert r.summary["discretisation"]["segments_on_shortest_wrap"] < 3
    # fewer segments than "auto" takes: no error is stated, and the run says why
    e = r.summary["discretisation"]["estimate"]
    assert "slip_largest" not in e and "150 segments against the 333" in e["unavailable"]


def _five_pk_at_80():
    """The resolution check's test drive: the 5PK at 80 segments of 15 mm, 0.3 s."""
    return drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                            {"simulation.duration": 0.3, "output.steady_window": [0.2, 0.3], "belt.segments": 80,
                             "output.segments": [0]})


def test_resolution_check_reports_the_change_against_a_coarser_run():
    """simulation.resolution_check runs the drive again at 0.7 x its segments: its estimate is that
    change times 1 / (1 / 0.7 - 1), checked here against a second run made by hand; an estimate over
    its target is a warning naming the quantity (the 5PK drive at 80 segments of 15 mm)."""
    from drivedyn.belt.segments.resolution import CHECK_RATIO, TENSION_TARGET

    base = _five_pk_at_80()
    r = drivedyn.run(drivedyn.replace(base, {"simulation.resolution_check": True}))
    e = r.summary["discretisation"]["estimate"]
    n2 = round(CHECK_RATIO * 80)
    assert e["coarse_segments"] == n2
    other = drivedyn.run(drivedyn.replace(base, {"belt.segments": n2})).summary
    factor = 1 / (80 / n2 - 1)
    for p in r.summary["pulleys"]:
        d = abs(r.summary["pulleys"][p]["slip"] - other["pulleys"][p]["slip"])
        assert e["slip"][p] == pytest.approx(d * factor, rel=1e-9, abs=1e-12)
    worst = 0.0
    for sp in r.summary["spans"]:
        for k in ("tension_min", "tension_mean", "tension_max"):
            a, b = r.summary["spans"][sp][k], other["spans"][sp][k]
            assert e["span_tension_relative"][sp][k] == pytest.approx(abs(a - b) * factor / abs(a), rel=1e-9)
            worst = max(worst, abs(a - b) * factor / abs(a))
    flagged = [d for d in r.diagnostics if d.code == "unconverged-resolution"]
    assert bool(flagged) == (worst > TENSION_TARGET or max(e["slip"].values()) > 3e-4)
    assert r.units["discretisation.estimate.slip_largest"] == "1"
    # the losses: the change at second order (the landing impacts fall as l^2), in W
    f2 = 1 / ((80 / n2) ** 2 - 1)
    la, lb = r.summary["power"]["losses"], other["power"]["losses"]
    for k in la:
        assert e["power_loss"][k] == pytest.approx(abs(la[k] - lb[k]) * f2, rel=1e-9, abs=1e-12)
    assert e["power_loss_relative"] == pytest.approx(sum(e["power_loss"].values()) / sum(map(abs, la.values())))
    assert r.units["discretisation.estimate.power_loss.contact_damping"] == "W"


def test_the_loss_estimate_against_a_refined_run():
    """The losses' estimate is second order: on the 5PK drive at 80 segments (checked at 56) it
    estimates the change of the losses to 320 segments within 30 % (0.57 against 0.47 W, nearly
    all friction; 640 segments lose 0.015 W less than 320), where the first-order factor of the
    slips and tensions would state 2.9 times the change."""
    base = _five_pk_at_80()
    r = drivedyn.run(drivedyn.replace(base, {"simulation.resolution_check": True}))
    est = sum(r.summary["discretisation"]["estimate"]["power_loss"].values())
    fine = drivedyn.run(drivedyn.replace(base, {"belt.segments": 320})).summary["power"]["losses"]
    real = abs(sum(r.summary["power"]["losses"].values()) - sum(fine.values()))
    assert 0.7 < est / real < 1.3


@pytest.mark.slow
def test_chord_sag_rule_converges_a_running_drives_torsional_mode():
    """A two-pulley drive (benchmarks/bench_chord_sag.py: 40 mm pulleys, 24 m/s, a torque pulse on
    the driven pulley) rings at its first torsional mode: at "auto" (chord sag 0.25 x the contact
    depth) within 1 % of twice the segments, while half of them (sag = depth: the landings shake
    the contact) ring more than 5 % low (measured: 299.0 / 298.7 Hz, 236.9 Hz at half)."""
    from bench_chord_sag import drive, ringing

    n = auto_segments(drive("auto"))[0]
    f = {k: ringing(drivedyn.run(drive(k))) for k in (n // 2, n, 2 * n)}
    assert f[n] == pytest.approx(f[2 * n], rel=0.01), f
    assert f[n // 2] < 0.95 * f[2 * n], f


@pytest.mark.slow
def test_rotation_scaling_where_the_chord_sag_is_resolved():
    """simulation.rotation_scaling (the segments' rotational inertia x 3.3, a longer step) where the
    chord sag is resolved leaves the running drive's torsional mode and losses as they were; at half
    the segments (sag = depth) the landings carry the losses and scaling raises them by a quarter.
    The two-pulley drive of benchmarks/bench_chord_sag.py at 24 m/s, semi-implicit (measured: 298.7
    against 299.0 Hz, losses 1.53 against 1.48 W at "auto"; 6.85 against 5.42 W at half, and 9.1
    against 5.0 W before the chain's grid-scale rotation mode was damped, system.GRID_ZETA)."""
    from bench_chord_sag import drive, ringing

    n = auto_segments(drive("auto"))[0]
    runs = {}
    for k in (n // 2, n):
        for rs in (True, False):
            m = drivedyn.replace(drive(k), {"simulation.method": "semi-implicit", "simulation.rotation_scaling": rs})
            r = drivedyn.run(m)
            runs[k, rs] = (r.summary["solver"], ringing(r), sum(r.summary["power"]["losses"].values()))
            assert r.summary["solver"]["rotation_scaling"] is rs
    assert runs[n, True][0]["step"] > 1.15 * runs[n, False][0]["step"]
    assert runs[n, True][1] == pytest.approx(runs[n, False][1], rel=0.005)
    assert runs[n, True][2] == pytest.approx(runs[n, False][2], rel=0.10)
    assert runs[n // 2, True][2] > 1.15 * runs[n // 2, False][2]


def test_the_overview_prints_the_stated_error():
    """The CLI's spans table carries the error the summary states, and says how it was found."""
    from drivedyn.front.overview import _resolution_note

    rule = {"segments": 333, "estimate": {"slip_largest": 1.6e-4, "tension_relative_largest": 0.032}}
    text = _resolution_note({"discretisation": rule})
    assert "(333 segments): slip within 0.016 points, span tensions within 3.2 %" in text and "rule" in text
    check = {"segments": 333, "estimate": {"slip_largest": 2e-4, "tension_relative_largest": 0.05, "coarse_segments": 233}}
    assert "the change against 233 segments" in _resolution_note({"discretisation": check})
    assert _resolution_note({"discretisation": {"segments": 80}}) == ""
    # a run-up states that its bins near a resonance carry more than the held-speed figure
    from drivedyn.belt.segments.resolution import rule_estimate

    fead = drivedyn.load(drivedyn.example_path("fead-runup"))
    e = rule_estimate(fead, 333, 333)
    assert "runup_note" in e and "runup_note" not in rule_estimate(drivedyn.replace(fead, {"output.runup_bin": None}),
                                                                   333, 333)
    assert "near a resonance" in _resolution_note({"discretisation": {"segments": 333, "estimate": e}})
