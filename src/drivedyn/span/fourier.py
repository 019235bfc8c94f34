"""Fourier analysis of the tooth-force signal over one tooth period.

The signal F(phi), phi in [0, 2 pi) standing for one tooth (seed fig. 2), is written

    F(phi) = mean + sum_k  c_k cos(k phi + theta_k),        c_k >= 0,

and the seed's F1 is c_1 (3.058 N for its polynomial). The normalised shape of the fluctuation
used by the Hill equation, F(t) = F0 + F1 Phi(t), is Phi = sum_k (c_k / c_1) cos(k omega t + theta_k),
so the first harmonic of Phi has unit amplitude as in the seed's eq. 6.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import ModelError


@dataclass(frozen=True)
class Harmonics:
    """Mean, amplitudes c_k and phases theta_k (k = 1..n) of a periodic signal.

    Attributes
    ----------
    mean : float
        Mean value (N).
    amplitudes : numpy.ndarray
        c_1..c_n (N).
    phases : numpy.ndarray
        theta_1..theta_n (rad).
    """

    mean: float
    amplitudes: np.ndarray
    phases: np.ndarray

    @property
    def f1(self) -> float:
        """First-harmonic amplitude F1 (N)."""
        return float(self.amplitudes[0])

    def shape(self):
        """(a_k, b_k) of Phi = sum a_k cos(k x) + b_k sin(k x), normalised so that c_1 = 1."""
        c1 = self.amplitudes[0]
        if c1 <= 0:
            return np.array([1.0]), np.array([0.0])  # no fluctuation: any unit shape gives mu = 0
        c = self.amplitudes / c1
        return c * np.cos(self.phases), -c * np.sin(self.phases)

    def evaluate(self, phi):
        """The truncated series at phase(s) phi (rad)."""
        k = np.arange(1, len(self.amplitudes) + 1)
        phi = np.asarray(phi, dtype=float)[..., None]
        return self.mean + np.sum(self.amplitudes * np.cos(k * phi + self.phases), axis=-1)


def _from_complex(mean, X) -> Harmonics:
    return Harmonics(float(mean), np.abs(X), np.angle(X))


def from_polynomial(coefficients, n: int = 10) -> Harmonics:
    """Harmonics of F(phi) = polyval(coefficients, phi) on [0, 2 pi) (coefficients highest first).

    The Fourier integrals are done with Gauss-Legendre quadrature of degree high enough to be
    exact for polynomial x trigonometric integrands of this size (to round-off).

    Examples
    --------
    >>> h = from_polynomial([0.00139, 0.0337, -0.685, 2.89, -1.71, 7.29])   # seed 002
    >>> round(h.f1, 3), round(h.mean, 2)
    (3.058, 10.24)
    """
    x, w = np.polynomial.legendre.leggauss(64 + 8 * n)
    phi = np.pi * (x + 1.0)
    w = np.pi * w
    f = np.polyval(np.asarray(coefficients, dtype=float), phi)
    k = np.arange(1, n + 1)[:, None]
    # X_k = (1/pi) int F e^{-i k phi} dphi: c_k = |X_k|, theta_k = arg X_k
    X = (f * w * np.exp(-1j * k * phi)).sum(axis=1) / np.pi
    return _from_complex((f * w).sum() / (2 * np.pi), X)


def from_samples(phi, force, n: int = 10) -> Harmonics:
    """Harmonics of samples over one tooth.

    Uniform samples over the period (with or without the closing point phi[0] + 2 pi, which is
    then averaged with the first, trapezoidal rule) are transformed directly by FFT: exact for
    trigonometric polynomials of degree below half the sample count. Other samples are joined
    linearly (periodically, last to first) and resampled finely before the FFT.
    """
    phi = np.asarray(phi, dtype=float)
    force = np.asarray(force, dtype=float)
    if phi.ndim != 1 or phi.shape != force.shape or len(phi) < 4:
        raise ModelError("needs at least 4 samples [phi, force]", field="tooth_force.samples")
    d = np.diff(phi)
    uniform = np.allclose(d, d.mean(), rtol=1e-6, atol=0.0)
    if uniform and abs(phi[-1] - phi[0] - 2 * np.pi) < 1e-6 * d.mean():
        f = np.r_[0.5 * (force[0] + force[-1]), force[1:-1]]
    elif uniform and abs(phi[-1] + d.mean() - phi[0] - 2 * np.pi) < 1e-6 * d.mean():
        f = force
    else:
        m = max(4096, 16 * n)
        f = np.interp(phi[0] + 2 * np.pi * np.arange(m) / m, phi, force, period=2 * np.pi)
    m = len(f)
    if n > (m - 1) // 2:
        raise ModelError(f"{m} samples resolve at most {(m - 1) // 2} harmonics, {n} asked (excitation.harmonics)",
                         field="tooth_force.samples")
    spectrum = np.fft.rfft(f) / m
    # the grid starts at phi[0]: shift the phase origin back to phi = 0
    X = 2.0 * spectrum[1:n + 1] * np.exp(-1j * np.arange(1, n + 1) * phi[0])
    return _from_complex(spectrum[0].real, X)


def from_series(t, force, period: float, n: int = 10) -> Harmonics:
    """Harmonics of a time series at the known period (e.g. from the belt simulator).

    Uses the last whole number of periods in the record and fits mean + n harmonics by least
    squares (exact for a periodic signal sampled on any grid).
    """
    t = np.asarray(t, dtype=float)
    force = np.asarray(force, dtype=float)
    if t.ndim != 1 or t.shape != force.shape or len(t) < 2 * n + 2:
        raise ModelError(f"needs at least {2 * n + 2} samples (time, force)", field="tooth_force.series")
    whole = np.floor((t[-1] - t[0]) / period)
    if whole < 1:
        raise ModelError(f"record of {t[-1] - t[0]:.4g} s is shorter than one tooth period {period:.4g} s",
                         field="tooth_force.series")
    keep = t >= t[-1] - whole * period
    tt, ff = t[keep], force[keep]
    x = 2 * np.pi * tt / period
    k = np.arange(1, n + 1)
    A = np.hstack([np.ones((len(x), 1)), np.cos(np.outer(x, k)), np.sin(np.outer(x, k))])
    coef, *_ = np.linalg.lstsq(A, ff, rcond=None)
    a, b = coef[1:n + 1], coef[n + 1:]
    return _from_complex(coef[0], a - 1j * b)


#: largest series file read (bytes): a million rows of two numbers
SERIES_BYTES = 50_000_000


def read_series(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a CSV (or whitespace) file with columns time (s), force (N); '#' comments allowed."""
    from pathlib import Path

    from ..core.model import read_capped

    p = Path(path)
    if not p.exists():
        raise ModelError(f"file {str(p)!r} not found", field="tooth_force.series")
    try:
        text = read_capped(p, "series", limit=SERIES_BYTES).replace(",", " ")
    except ModelError as exc:
        raise ModelError(str(exc), field="tooth_force.series") from None
    try:
        data = np.loadtxt(text.splitlines(), comments="#", ndmin=2)
    except ValueError as exc:
        raise ModelError(f"cannot read {str(p)!r} as two numeric columns: {exc}", field="tooth_force.series") from None
    if data.shape[1] < 2:
        raise ModelError(f"{str(p)!r} needs two columns (time, force)", field="tooth_force.series")
    return data[:, 0], data[:, 1]
