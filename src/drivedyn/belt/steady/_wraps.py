"""Closed forms of the belt on a wrap, shared by the modes (modes.py) and the rotational model's
step (rotational/_kernels.py): the depth the belt sinks to under its pressure, and its axial
stiffness there (EA in series with the sinking). Plain Python (check's modes run them without
numba); the rotational kernels compile them."""
import math


def sunk_depth(q, c1, c2):
    """Depth p (m) at which the contact law carries q (N/m): c1 p^2 + c2 p = q (placement.penetration)."""
    if q <= 0.0:
        return 0.0
    return 2.0 * q / (c2 + math.sqrt(c2 * c2 + 4.0 * c1 * q))


def wrap_axial_stiffness(EA, c1, c2, q, r):
    """Axial stiffness (N) of the belt on a wrap of radius r that it presses at q = N / length
    (N/m): its EA in series with its sinking into the rim. A tension change dT changes the pressure
    by dT / r and the depth p by dT / (r k_n), k_n = c2 + 2 c1 p the contact law's tangent stiffness
    per unit length at c1 p^2 + c2 p = q; the belt's centre line then runs on a circle shorter by dp
    / r, which lets belt out of the wrap as a strain would: 1 / EA_w = 1 / EA + 1 / (r^2 k_n)
    (the segment model's wraps, measured: a static torque turns the tensioned drive of
    tests/belt/test_modes_tensioner.py within 0.4 % of belt/steady/modes.py with it, 6 % more without)."""
    kn = c2 + 2.0 * c1 * sunk_depth(q, c1, c2)
    if kn <= 0.0:
        return EA
    return 1.0 / (1.0 / EA + 1.0 / (r * r * kn))
