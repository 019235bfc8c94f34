"""Installation table: span frequencies at the installation tension and back, from the same belt data."""
import math

import pytest

import drivedyn
from drivedyn.belt.geometry.installation import installation_table, table_lines, tension_from_span_frequency
from drivedyn.mechanics.layout import compute_layout


@pytest.fixture(scope="module")
def drive():
    m = drivedyn.load(drivedyn.example_path("belt-accessory"))
    return m, compute_layout(m)


def test_frequencies_follow_the_taut_beam_formula(drive):
    m, lay = drive
    T0, mu, EI = 600.0, m.belt.mass_per_length, m.belt.bending_stiffness
    tab = installation_table(m, T0, lay, tolerance=0.1)
    for sp in lay.spans:
        row = tab["spans"][sp.name]
        L = sp.length
        # written out here: f = (1/2L) sqrt((T + pi^2 EI / L^2) / m')
        assert row["frequency"] == pytest.approx(math.sqrt((T0 + math.pi ** 2 * EI / L ** 2) / mu) / (2 * L), rel=1e-12)
        assert row["frequency_string"] == pytest.approx(math.sqrt(T0 / mu) / (2 * L), rel=1e-12)
        # +-10 % tension is about +-5 % frequency (f ~ sqrt(T))
        lo, hi = row["band"]
        assert lo < row["frequency"] < hi
        assert hi / row["frequency"] == pytest.approx(math.sqrt(1.1), rel=0.01)
    assert tab["measure_on"] == max(lay.spans, key=lambda s: s.length).name


def test_measured_frequency_gives_back_the_tension(drive):
    m, lay = drive
    tab = installation_table(m, 450.0, lay)
    for name, row in tab["spans"].items():
        assert tension_from_span_frequency(m, lay, name, row["frequency"]) == pytest.approx(450.0, rel=1e-8)
    with pytest.raises(drivedyn.ModelError, match="no span named"):
        tension_from_span_frequency(m, lay, "nope", 50.0)


def test_report_lines(drive):
    m, lay = drive
    lines = table_lines(installation_table(m, 550.0, lay))
    assert len(lines) == 2 + len(lay.spans) and sum("measure here" in ln for ln in lines) == 1
