"""The 4-point Lagrange cubic both belt models read their geometry tables by: its weights, and a
periodic table's value and derivative (the rotational model's curve and tensioner tables, the segment
model's contact curves). Compiled inline into the kernels that call them."""
import math

from numba import njit


@njit(cache=True, inline="always")
def _cubic(f):
    """Weights of the 4-point Lagrange cubic through nodes -1, 0, 1, 2 at fraction f, and of its
    derivative (per grid step)."""
    wm = -f * (f - 1.0) * (f - 2.0) / 6.0
    w0 = (f + 1.0) * (f - 1.0) * (f - 2.0) / 2.0
    w1 = -(f + 1.0) * f * (f - 2.0) / 2.0
    w2 = (f + 1.0) * f * (f - 1.0) / 6.0
    dm = -(3.0 * f * f - 6.0 * f + 2.0) / 6.0
    d0 = (3.0 * f * f - 4.0 * f - 1.0) / 2.0
    d1 = -(3.0 * f * f - 2.0 * f - 2.0) / 2.0
    d2 = (3.0 * f * f - 1.0) / 6.0
    return wm, w0, w1, w2, dm, d0, d1, d2


@njit(cache=True, inline="always")
def _periodic(tab, a, th, P):
    """The cubic through tab[a]'s four nodes about th on its period P (N nodes), and its derivative in th."""
    n = tab.shape[1]
    d = P / n
    x = (th % P) / d
    i = int(math.floor(x))
    wm, w0, w1, w2, dm, d0, d1, d2 = _cubic(x - i)
    im, i1, i2 = (i - 1) % n, (i + 1) % n, (i + 2) % n
    i = i % n
    v = wm * tab[a, im] + w0 * tab[a, i] + w1 * tab[a, i1] + w2 * tab[a, i2]
    return v, (dm * tab[a, im] + d0 * tab[a, i] + d1 * tab[a, i1] + d2 * tab[a, i2]) / d
