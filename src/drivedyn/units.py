"""Units at the edge: strings such as "27 mm" or "1450 rpm" become SI floats once, at load time.

Nothing inside a solver sees pint. The registry is created lazily, on the first string value,
so that importing drivedyn stays fast.
"""
from __future__ import annotations

import functools

from .errors import ModelError


@functools.lru_cache(maxsize=1)
def registry():
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("rev = revolution")  # so that "4 rev/s" reads as engineers write it

    return ureg


def to_si(value, unit: str) -> float:
    """Return ``value`` as a float in the SI ``unit``.

    Numbers are taken as already in ``unit``; strings are parsed with pint ("27 mm",
    "15 N*m", "4 rev/s") and converted. Raises ModelError on an incompatible or malformed value.
    """
    if isinstance(value, bool):
        raise ModelError(f"expected a number or a quantity in {unit}, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        ureg = registry()
        try:
            q = ureg.Quantity(value.strip())
        except Exception:
            raise ModelError(f"cannot read {value!r} as a quantity (expected e.g. '1.5 {unit}')") from None
        try:
            if unit in ("", "1"):
                return float(q.to("dimensionless").magnitude)
            return float(q.to(unit).magnitude)
        except Exception:
            raise ModelError(f"{value!r} is not compatible with {unit!r}") from None
    raise ModelError(f"expected a number or a quantity in {unit}, got {value!r}")
