"""The seed's numbers (Belyaev, seed 002), Fourier analysis, the model file, run/check end to end,
the belt-drive reference, and bad input (one line naming the field, exit status 2)."""
import json

import numpy as np
import pytest

import drivedyn
from drivedyn.front.cli import main
from drivedyn.span import fourier
from drivedyn.mechanics.span.quantities import critical_speed, natural_frequency

SEED_POLY = [0.00139, 0.0337, -0.685, 2.89, -1.71, 7.29]


def test_seed_f1_and_mean_from_polynomial():
    h = fourier.from_polynomial(SEED_POLY)
    assert h.f1 == pytest.approx(3.058, abs=5e-4)     # seed: F1 = 3.058 N
    assert h.mean == pytest.approx(10.24, abs=5e-3)   # design note: mean 10.24 N


def test_fourier_of_samples_and_series_converge_to_polynomial():
    exact = fourier.from_polynomial(SEED_POLY, 4)
    errs = []
    for m in (51, 201, 801):   # closing point included: the polynomial jumps there (trapezoidal rule)
        phi = np.linspace(0, 2 * np.pi, m)
        errs.append(abs(fourier.from_samples(phi, np.polyval(SEED_POLY, phi), 4).f1 - exact.f1))
    assert errs[2] < errs[1] < errs[0] and errs[2] < 2e-3
    period = 4e-3
    t = np.arange(0, 0.1, period / 4000)
    series = fourier.from_series(t, np.polyval(SEED_POLY, 2 * np.pi * ((t / period) % 1.0)), period, 4)
    assert series.f1 == pytest.approx(exact.f1, rel=2e-3)
    assert series.phases[0] == pytest.approx(exact.phases[0], abs=2e-3)


def test_harmonic_series_reconstructs_a_trig_polynomial():
    phi = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    f = 2.0 + 1.5 * np.cos(phi - 0.3) + 0.4 * np.cos(3 * phi + 1.0)
    h = fourier.from_samples(phi, f, 4)
    assert h.amplitudes == pytest.approx([1.5, 0.0, 0.4, 0.0], abs=1e-12)   # uniform samples: exact DFT
    assert h.evaluate(phi) == pytest.approx(f, abs=1e-12)
    closed = np.linspace(0, 2 * np.pi, 65)                                     # with the closing point
    g = fourier.from_samples(closed, 2.0 + 1.5 * np.cos(closed - 0.3) + 0.4 * np.cos(3 * closed + 1.0), 4)
    assert g.amplitudes == pytest.approx(h.amplitudes, abs=1e-12)
    assert g.phases[[0, 2]] == pytest.approx([-0.3, 1.0], abs=1e-12)
    uneven = np.sort(np.random.default_rng(1).uniform(0, 2 * np.pi, 400))     # linear interpolation
    u = fourier.from_samples(uneven, 2.0 + 1.5 * np.cos(uneven - 0.3), 2)
    assert u.f1 == pytest.approx(1.5, rel=1e-3)


def test_seed_span_quantities(seed_span):
    assert seed_span.euler_load == pytest.approx(np.pi ** 2 * 0.045 / 0.09, rel=1e-14)   # 4.9348 N
    assert float(critical_speed(100.0, seed_span)) == pytest.approx(np.sqrt(104.9348022 / 0.084), rel=1e-8)
    # the seed's printed Omega = (pi^2/l^2) sqrt(EI/rhoA (F0+F*-V^2 rhoA)/F*) equals ours
    F0, V = 100.0, 5.0
    printed = np.pi ** 2 / 0.09 * np.sqrt(0.045 / 0.084 * (F0 + seed_span.euler_load - V ** 2 * 0.084) / seed_span.euler_load)
    assert float(natural_frequency(F0, V, seed_span)) == pytest.approx(printed, rel=1e-12)
    assert np.isnan(natural_frequency(F0, 40.0, seed_span))


def test_seed_convention_halves_the_band(span_model):
    a = drivedyn.run(span_model(chart__floquet=False)).summary["resonance_bands"][0]
    b = drivedyn.run(span_model(excitation__period="seed", chart__floquet=False)).summary["resonance_bands"][0]
    # omega doubles at the same speed; the band moves to about half the speed (the V^2 rhoA
    # term of the effective tension is what keeps it from being exactly half)
    assert b == pytest.approx([a[0] / 2, a[1] / 2], rel=1e-3)
    assert b[0] > a[0] / 2 and b[1] > a[1] / 2


def test_example_runs_end_to_end(tmp_path):
    """The shipped example (smaller grids) through the command line: files and summary keys."""
    text = drivedyn.example_path("span-t10").read_text().replace("points = [200, 200]", "points = [40, 40]")
    text = text.replace("points = [160, 160]", "points = [30, 30]")
    f = tmp_path / "span.toml"
    f.write_text(text + "\n[response]\nduration = \"0.05 s\"\nmoment_amplitude = \"0.01 N*m\"\n")
    out = tmp_path / "out"
    assert main(["run", str(f), "-o", str(out), "-q"]) == 0
    s = json.loads((out / "summary.json").read_text())
    for key in ("pretension", "speed", "v_critical", "euler_load", "omega", "f1", "resonance_bands", "measurement"):
        assert key in s
    assert s["f1"] == pytest.approx(3.058, abs=5e-4)
    (v0, v1), = s["resonance_bands"]
    assert v0 < 1.11 < v1 and s["in_resonance"]
    assert s["measurement"]["tension"] > 0 and s["measurement"]["uncertainty"] > 0
    res = drivedyn.open_result(out)
    assert res.ds["floquet_multiplier"].dims == ("pretension", "speed")
    assert res.ds["floquet_multiplier"].shape == (40, 40)
    assert res.ds["region"].attrs["units"] == "1"
    # undamped, at the model point inside the tongue, the modal coordinate grows
    assert s["response"]["max_deflection"] > 1e-4
    for png in ("span-chart.png", "span-tongue.png", "span-floquet.png", "span-frequencies.png", "span-response.png"):
        assert (out / png).stat().st_size > 10_000


def test_check_prints_span_quantities(capsys):
    assert main(["check", str(drivedyn.example_path("span-t10"))]) == 0
    out = capsys.readouterr().out
    for word in ("F* = 4.935 N", "V_cr = 35.34 m/s", "F1 = 3.058 N", "principal band", "measurement"):
        assert word in out


@pytest.mark.parametrize("name", ["span-t10", "span-t10-seed"])
def test_model_round_trip(name):
    m = drivedyn.load(drivedyn.example_path(name))
    assert drivedyn.loads(drivedyn.dumps(m)) == m


def test_span_from_belt_drive_model(span_model):
    """The span length comes from the belt-drive layout (5PK seed: 515 mm between equal pulleys)."""
    pytest.importorskip("drivedyn.mechanics.layout")
    m = span_model(span__length=None, span__belt_model="belt-5pk.toml", span__span_name="driver-driven",
                   span__mass_per_length=None, span__bending_stiffness=None, operation__pretension=None)
    r = drivedyn.run(m.model_copy(update={"chart": m.chart.model_copy(update={"floquet": False})}))
    assert r.summary["span_length"] == pytest.approx(0.515, rel=1e-9)
    assert r.summary["mass_per_length"] == pytest.approx(0.096)
    assert r.summary["pretension"] == pytest.approx(550.0)


def test_belt_reference_errors(span_model):
    m = span_model(span__length=None, span__belt_model="belt-5pk.toml", span__span_name="nowhere")
    with pytest.raises(drivedyn.ModelError, match=r"^span.span_name: no span named 'nowhere'"):
        drivedyn.run(m)
    m = span_model(span__length=None, span__belt_model="/nonexistent/belt.toml", span__span_name="a-b")
    with pytest.raises(drivedyn.ModelError, match=r"^span.belt_model: .*not found"):
        drivedyn.check(m)


GOOD = None


def _good():
    return drivedyn.example_path("span-t10").read_text()


@pytest.mark.parametrize("old, new, expect", [
    ('pretension = "100 N"', 'pretension = "-100 N"', "operation.pretension: must be > 0 N, got -100 N"),
    ('length = "0.3 m"', 'length = "0 m"', "span.length: must be > 0 m, got 0 m"),
    ('speed = "1.11 m/s"', 'speed = "40 m/s"\n[response]', "operation.speed: 40 m/s is at or above the critical speed"),
    ('frequency = "58 Hz"', 'frequency = "5 Hz"', "measurement.frequency: 5 Hz is below"),
    ('teeth = 16', 'teeth = 0', "excitation.teeth: must be >= 1"),
    ('area = "2.8e-5 m^2"', 'area = "2.8e-5 m"', "span.area"),
    ('damping_ratio = 0.0', 'damping_ration = 0.0', "did you mean 'damping_ratio'"),
    ('polynomial = [', 'amplitude = 3.0\npolynomial = [', "exactly one of tooth_force"),
    ('pretension = ["0 N", "300 N"]', 'pretension = ["300 N", "0 N"]', "chart.pretension: must be [low, high]"),
])
def test_bad_input_one_line_naming_the_field(tmp_path, capsys, old, new, expect):
    text = _good()
    assert old in text
    f = tmp_path / "m.toml"
    f.write_text(text.replace(old, new, 1))
    assert main(["check", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert expect in err, err


def test_growth_rate_floquet_vs_response_vs_first_order_theory(span_model):
    """At the tongue centre, the undamped growth rate is mu Omega / 2 (Nayfeh & Mook 1979, sec. 5.2);
    the Floquet multiplier and the integrated response (no moment forcing) must agree with it."""
    from drivedyn.mechanics.span.mathieu import tongue_centre_speed
    from drivedyn.mechanics.span.quantities import SpanProperties

    vc = float(tongue_centre_speed(100.0, 1, SpanProperties(0.3, 0.084, 0.045), 16, 2 * np.pi * 0.024 / 16))
    m = span_model(operation__speed=vc, tooth_force__polynomial=None, tooth_force__amplitude=3.058,
                   chart__floquet=False, response={"duration": 1.0, "points": 4000})
    s = drivedyn.run(m).summary
    theory = s["mu"] * s["omega"] / 2
    assert s["growth_rate"] == pytest.approx(theory, rel=0.02)
    r = drivedyn.run(m)
    q, t = r.ds["modal_coordinate"].values, r.ds["time"].values
    env = [np.abs(q[(t >= a) & (t < a + 0.1)]).max() for a in (0.1, 0.8)]
    assert np.log(env[1] / env[0]) / 0.7 == pytest.approx(s["growth_rate"], rel=0.05)


def test_tooth_force_from_samples_and_series_files(span_model, tmp_path):
    """The three tooth-force inputs of a model give the same F1 for the same signal."""
    phi = np.linspace(0, 2 * np.pi, 401)
    rows = [[float(p), float(np.polyval(SEED_POLY, p))] for p in phi]
    a = drivedyn.check(span_model(tooth_force__polynomial=None, tooth_force__samples=rows))
    period = 2 * np.pi * 0.024 / 16 / 5.0          # tooth-passing period at 5 m/s
    t = np.arange(0, 20 * period, period / 500)
    csv = tmp_path / "force.csv"
    np.savetxt(csv, np.c_[t, np.polyval(SEED_POLY, 2 * np.pi * ((t / period) % 1.0))], delimiter=",",
               header="time (s), force (N)")
    b = drivedyn.check(span_model(tooth_force__polynomial=None, tooth_force__series=str(csv)))
    assert "F1 = 3.058 N" in a and "F1 = 3.058 N" in b
    with pytest.raises(drivedyn.ModelError, match=r"^tooth_force.series: file"):
        drivedyn.check(span_model(tooth_force__polynomial=None, tooth_force__series=str(tmp_path / "none.csv")))


def test_diverged_operating_point_is_reported_not_an_error(span_model):
    s = drivedyn.run(span_model(operation__speed=40.0, chart__floquet=False)).summary
    assert s["stability"] == "divergence" and not s["stable"]
    assert s["omega"] is None and s["frequencies"] is None
    assert s["critical_speed_margin"] == pytest.approx(s["v_critical"] - 40.0)
    assert s["floquet_multiplier"] > 1
    assert "DIVERGES" in drivedyn.check(span_model(operation__speed=40.0))
    ok = drivedyn.run(span_model(chart__floquet=False)).summary
    assert ok["stability"] == "stable" and ok["stable"]


def test_belt_model_path_relative_to_the_model_file(tmp_path):
    pytest.importorskip("drivedyn.mechanics.layout")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "mybelt.toml").write_text(drivedyn.example_path("belt-5pk").read_text())
    f = tmp_path / "sub" / "span.toml"
    f.write_text('kind = "span-stability"\n[span]\nbelt_model = "mybelt.toml"\nspan_name = "driver-driven"\n'
                 '[excitation]\npulley_radius = "27 mm"\n[tooth_force]\namplitude = 5.0\n')
    assert "l = 0.515 m" in drivedyn.check(f)
