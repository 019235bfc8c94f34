"""Span runs above the critical speed warn (above-critical-speed); V = 0 prints no NaN or inf."""
import math
import subprocess
import sys

import pytest

import drivedyn
from drivedyn.core.results import flatten

SMALL = {"chart.points": [12, 12], "chart.zoom.points": [8, 8]}


def span(**over):
    m = drivedyn.load(drivedyn.example_path("span-t10"))
    return drivedyn.replace(m, {**SMALL, **over})


def test_above_critical_speed_warns_with_v_and_v_cr():
    m = span(**{"operation.speed": 60.0})
    r = drivedyn.run(m)
    # V_cr = sqrt((F0 + pi^2 EI / l^2) / rhoA), computed here from the example's data
    vcr = math.sqrt((100 + math.pi ** 2 * 0.045 / 0.3 ** 2) / (3e3 * 2.8e-5))
    d = [x for x in r.diagnostics if x.code == "above-critical-speed"]
    assert r.status == "warning" and len(d) == 1
    assert d[0].value == pytest.approx(60.0) and d[0].limit == pytest.approx(vcr, rel=1e-9) and d[0].unit == "m/s"
    assert drivedyn.run(span(**{"operation.speed": 0.999 * vcr})).status == "success"


def test_cli_text_and_exit_agree_above_critical_speed(tmp_path):
    text = drivedyn.example_path("span-t10").read_text().replace('speed = "1.11 m/s"', 'speed = "60 m/s"')
    text = text.replace("points = [200, 200]", "points = [12, 12]").replace("points = [160, 160]", "points = [8, 8]")
    f = tmp_path / "fast.toml"
    f.write_text(text)
    p = subprocess.run([sys.executable, "-m", "drivedyn.front.cli", "run", str(f), "-o", str(tmp_path / "o"), "-q",
                        "--no-plots"], capture_output=True, text=True)
    assert p.returncode == 0 and "above-critical-speed" in p.stderr + p.stdout
    p = subprocess.run([sys.executable, "-m", "drivedyn.front.cli", "run", str(f), "-o", str(tmp_path / "o2"), "-q",
                        "--no-plots", "--strict"], capture_output=True, text=True)
    assert p.returncode == 3


def test_zero_speed_has_no_nan_or_inf():
    from drivedyn.span.report import report

    m = span(**{"operation.speed": 0.0})
    text = report(m)
    assert "nan" not in text.lower() and "inf " not in text.lower() and "inf ms" not in text
    r = drivedyn.run(m)
    assert r.status == "success"
    bad = {k: v for k, v in flatten(r.summary).items() if isinstance(v, float) and not math.isfinite(v)}
    assert not bad
    assert r.units["v_critical"] == "m/s" and r.units["pretension"] == "N"


def test_above_critical_speed_report_has_no_nan():
    from drivedyn.span.report import report

    assert "nan" not in report(span(**{"operation.speed": 60.0})).lower()


def test_operating_point_in_a_tongue_warns():
    """span-t10 sits in the principal tongue on purpose (its comment, summary in_resonance): the
    status says so with the Floquet multiplier; well below the tongue's speeds the span is stable."""
    r = drivedyn.run(span())
    d = [x for x in r.diagnostics if x.code == "parametric-resonance"]
    assert r.summary["in_resonance"] and r.summary["floquet_multiplier"] > 1
    assert r.status == "warning" and len(d) == 1 and d[0].value == pytest.approx(r.summary["floquet_multiplier"])
    calm = drivedyn.run(span(**{"operation.speed": 0.3}))
    assert calm.summary["floquet_multiplier"] <= 1 + 1e-6
    assert not [x for x in calm.diagnostics if x.code == "parametric-resonance"]


def test_the_operating_point_table_reads_in_words_and_hz():
    """The span's table printed summary ids (natural_frequency_hz, v_critical) and the excitation in
    rad/s (740) beside frequencies in Hz; the belt and gear tables read in words and engineering units."""
    import math

    from drivedyn.front.overview import tables

    r = drivedyn.run(drivedyn.load(drivedyn.example_path("span-t10")))
    table = next(t for t in tables(r) if t["title"] == "span at the operating point")
    rows = {row[0]: row for row in table["rows"]}
    assert "natural_frequency_hz" not in rows and "v_critical" not in rows
    exc = rows["excitation frequency (tooth passing)"]
    assert exc[2] == "Hz" and float(exc[1]) == pytest.approx(r.summary["excitation_frequency"] / (2 * math.pi), rel=1e-4)
    assert rows["first natural frequency"][2] == "Hz" and rows["critical speed of the span"][2] == "m/s"
