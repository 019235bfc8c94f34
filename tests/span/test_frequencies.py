"""Reference tests of span frequencies and the tension-from-frequency method.

Sources: string f_n = (n/2L) sqrt(T/m) (Rayleigh, Theory of Sound, sec. 127); pinned tensioned
beam f_n = (n/2L) sqrt((T + n^2 pi^2 EI/L^2)/m) (exact, sine modes); axially moving string
f_n = (n/2L) c (1 - V^2/c^2) (Mote 1965; Wickert & Mote 1990, J. Appl. Mech. 57, eq. 22).
"""
import numpy as np
import pytest

from drivedyn import ModelError
from drivedyn.mechanics.span.frequencies import beam_frequency, estimate_tension, moving_beam_frequencies, moving_string_frequency, string_frequency, tension_from_frequency

T, M, L = 120.0, 0.084, 0.3


def test_string_formula_closed_form():
    n = np.arange(1, 4)
    # T = 120 N, m = 0.084 kg/m: c = 37.796 m/s; f1 = c / 2L
    assert string_frequency(T, M, L, n) == pytest.approx(n * np.sqrt(T / M) / (2 * L), rel=1e-14)
    assert float(string_frequency(T, M, L)) == pytest.approx(62.99407883487120, rel=1e-12)
    # the Galerkin model with EI = 0 and V = 0 is the string exactly (sine modes)
    assert moving_beam_frequencies(T, M, L, 0.0, 0.0, 3) == pytest.approx(string_frequency(T, M, L, n), rel=1e-12)


def test_beam_galerkin_exact_at_rest():
    n = np.arange(1, 4)
    assert moving_beam_frequencies(T, M, L, 0.045, 0.0, 3) == pytest.approx(beam_frequency(T, M, L, 0.045, n), rel=1e-12)


@pytest.mark.parametrize("V", [5.0, 20.0, 35.0])
def test_moving_string_galerkin_converges_to_mote(V):
    """The gyroscopic Galerkin model converges to the exact moving-string frequencies."""
    n = np.arange(1, 4)
    exact = moving_string_frequency(T, M, L, V, n)
    err = [np.max(np.abs(moving_beam_frequencies(T, M, L, 0.0, V, 3, terms=J) / exact - 1)) for J in (8, 16, 32)]
    assert err[-1] < 1e-4 * (1 + V / 10)
    assert err[2] < err[1] < err[0]


@pytest.mark.parametrize("EI, V, n", [(0.0, 0.0, 1), (0.045, 0.0, 1), (0.045, 10.0, 1), (0.045, 10.0, 2), (0.2, 25.0, 3)])
def test_round_trip_tension_frequency_tension(EI, V, n):
    f = moving_beam_frequencies(T, M, L, EI, V, n)[n - 1]
    assert tension_from_frequency(f, M, L, EI, V, n) == pytest.approx(T, rel=1e-9)


def test_corrections_add_up_and_have_the_right_sign():
    f = moving_beam_frequencies(T, M, L, 0.045, 10.0, 1)[0]
    e = estimate_tension(f, M, L, 0.045, 10.0)
    assert e.tension == pytest.approx(T, rel=1e-9)
    assert e.tension_string + e.bending_correction + e.speed_correction == pytest.approx(e.tension, rel=1e-12)
    assert e.bending_correction == pytest.approx(-np.pi ** 2 * 0.045 / L ** 2, rel=1e-6)   # -F* exactly (pinned)
    assert e.speed_correction > 0      # a moving span sounds lower: the string formula underestimates


def test_uncertainty_string_case_first_order():
    """For the string, sigma_T/T = sqrt((2 sf/f)^2 + (2 sL/L)^2 + (sm/m)^2)."""
    f = float(string_frequency(T, M, L))
    e = estimate_tension(f, M, L, sigma_f=0.3, sigma_L=0.002, sigma_m=0.003)
    rel = np.sqrt((2 * 0.3 / f) ** 2 + (2 * 0.002 / L) ** 2 + (0.003 / M) ** 2)
    assert e.uncertainty == pytest.approx(rel * T, rel=1e-5)
    assert e.contributions["mass"] == pytest.approx(0.003 / M * T, rel=1e-5)


def test_speed_above_critical_is_a_model_error():
    with pytest.raises(ModelError, match=r"^speed: .*critical speed"):
        moving_beam_frequencies(10.0, M, L, 0.0, 50.0)


def test_frequency_below_zero_tension_frequency_is_a_model_error():
    with pytest.raises(ModelError, match=r"^frequency: "):
        tension_from_frequency(5.0, M, L, 0.045)   # bending alone gives ~12 Hz
