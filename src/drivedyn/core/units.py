"""Units at the edge: strings such as "27 mm" or "1450 rpm" become SI floats once, at load time.

Nothing inside a solver sees pint. The registry is created lazily, on the first string value,
so that importing drivedyn stays fast. This is also the one place where a number read from a
model is refused when it is not finite (NaN, inf, or a string that overflows such as "1e400 m").
"""
from __future__ import annotations

import functools
import math
import re

from .errors import ModelError

# "<number> <unit expression>": the common form, converted with a cached factor per unit so that a
# long table costs one pint parse per distinct unit, not one per cell
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_SIMPLE = re.compile(rf"\s*({_NUMBER})\s*([A-Za-z_][A-Za-z0-9_*/^ .()\-]*)?\s*")
# a power operator and what follows it: only a small literal exponent, not itself raised again
_POWER = re.compile(r"(\*\*|\^)\s*")
_SMALL_EXPONENT = re.compile(r"\(?\s*[-+]?\d{1,2}(?:\.\d+)?(?![\d.])\s*\)?")
#: longest quantity string read (a unit expression, not a program)
MAX_LENGTH = 100
#: magnitudes read from a model lie in [TINY, HUGE] (or are 0), in SI. The shipped models span
#: 1e-12 (a tolerance) to 4e11 (a contact stiffness); outside 1e-30..1e30 no transmission quantity
#: makes sense, and inside it a product of up to ten quantities stays within the float range
#: (1e308), so the solvers' derived quantities cannot overflow to inf or divide by an underflow.
HUGE = 1e30
TINY = 1e-30


@functools.lru_cache(maxsize=1)
def registry():
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("rev = revolution")  # so that "4 rev/s" reads as engineers write it

    return ureg


def _check_powers(text: str) -> None:
    """Refuse exponents that are not small literal numbers ("9**9**9 m" would make pint compute a
    number with 370 million digits): every "**" or "^" must be followed by at most two digits and
    not by another power."""
    for m in _POWER.finditer(text):
        rest = text[m.end():]
        e = _SMALL_EXPONENT.match(rest)
        if e is None or _POWER.match(rest[e.end():].lstrip()):
            raise ModelError(f"cannot read {text!r} as a quantity: exponents must be small numbers (e.g. 'm^2')")


def finite(x: float, shown=None) -> float:
    """``x`` if it is a finite number of sensible magnitude (0 or TINY..HUGE), else ModelError
    ("must be a finite number, got nan")."""
    if not math.isfinite(x):
        raise ModelError(f"must be a finite number, got {x if shown is None else shown}")
    if x != 0 and not TINY <= abs(x) <= HUGE:
        raise ModelError(f"magnitude {abs(x):.3g} (SI) is outside {TINY:g}..{HUGE:g}, got {x if shown is None else shown}")
    return x


#: factors of the units the shipped models write, known without building the pint registry (which
#: costs about 0.8 s, most of a ``drivedyn check``); each equals pint's factor exactly (tested in
#: tests/api/test_bad_values.py), and a unit written as its SI target has the factor 1
KNOWN_FACTORS = {
    ("mm", "m"): 0.001, ("cm", "m"): 0.01, ("um", "m"): 1e-06, ("km", "m"): 1000.0,
    ("MPa", "Pa"): 1000000.0, ("GPa", "Pa"): 1000000000.0, ("kPa", "Pa"): 1000.0,
    ("N/mm^2", "Pa"): 1000000.0, ("MPa", "N/m^2"): 1000000.0,
    ("kW", "W"): 1000.0, ("kN", "N"): 1000.0, ("kHz", "Hz"): 1000.0,
    ("g", "kg"): 0.001, ("g/m", "kg/m"): 0.001, ("kg*mm^2", "kg*m^2"): 1e-06,
    ("deg", "rad"): 0.017453292519943295, ("N*m/deg", "N*m/rad"): 57.29577951308232,
    ("h", "s"): 3600.0, ("min", "s"): 60.0, ("ms", "s"): 0.001,
    ("rpm", "rad/s"): 0.10471975511965977, ("rev/s", "rad/s"): 6.283185307179586,
    ("rpm/s", "rad/s^2"): 0.10471975511965977,
    ("N/mm", "N/m"): 1000.0, ("kN/mm", "N/m"): 1000000.0, ("N*mm", "N*m"): 0.001,
    ("mm^2/s", "m^2/s"): 1e-06, ("N*m*s", "N*m*s/rad"): 1.0,
}


@functools.lru_cache(maxsize=256)
def _factor(unit_text: str, unit: str) -> float | None:
    """SI factor of ``unit_text`` in ``unit``, or None if the conversion is not a plain factor
    (offset units such as degC) or not possible (the full path then reports why)."""
    if unit_text == unit and unit not in ("", "1"):
        return 1.0
    known = KNOWN_FACTORS.get((unit_text, unit))
    if known is not None:
        return known
    ureg = registry()
    target = "dimensionless" if unit in ("", "1") else unit
    try:
        one = float(ureg.Quantity(1.0, unit_text).to(target).magnitude)
        two = float(ureg.Quantity(2.0, unit_text).to(target).magnitude)
    except Exception:
        return None
    return one if math.isfinite(one) and two == 2.0 * one else None


#: SI units per angle, in which the angle is dimensionless to pint (and SI): a text without an angle
#: ("0.4 N*m" for a torsional rate) would read per radian, 57.3 times softer than per degree, silently
PER_ANGLE = {"N*m/rad"}
_ANGLE = re.compile(r"(?<![A-Za-z])(rad|radians?|deg|degrees?|rev|revolutions?|turns?|arcmin|arcsec|grad|gon)(?![A-Za-z])")


def _check_angle(text: str, unit: str) -> None:
    if unit in PER_ANGLE and re.search(r"[A-Za-z]", text) and not _ANGLE.search(text):
        num = text.split()[0] if text.split() else text
        raise ModelError(f"{text!r} has no angle in its unit, and a torsional rate is per angle: write "
                         f"'{num} {unit}' or, as suppliers print it, '{num} {unit.replace('rad', 'deg')}' (per degree "
                         "it is 57.3 times stiffer)")


def _parse(text: str, unit: str) -> float:
    if len(text) > MAX_LENGTH:
        raise ModelError(f"cannot read a {len(text)}-character string as a quantity (expected e.g. '1.5 {unit}')")
    _check_powers(text)
    _check_angle(text, unit)
    m = _SIMPLE.fullmatch(text)
    if m is not None:
        number, unit_text = float(m.group(1)), (m.group(2) or "").strip()
        if not unit_text and unit in ("", "1"):
            return number
        if unit_text:
            factor = _factor(unit_text, unit)
            if factor is not None:
                return number * factor
    ureg = registry()
    try:
        q = ureg.Quantity(text)
    except Exception:
        raise ModelError(f"cannot read {text!r} as a quantity (expected e.g. '1.5 {unit}')") from None
    try:
        if unit in ("", "1"):
            return float(q.to("dimensionless").magnitude)
        return float(q.to(unit).magnitude)
    except Exception:
        hint = ""
        if re.search(r"(?<![A-Za-z])Nm(?![A-Za-z])", text):
            # engineers write newton-metres as "Nm": pint (and SI) read it as nanometre
            hint = f": 'Nm' reads as nanometre, write newton-metres as 'N*m' (e.g. '{text.replace('Nm', 'N*m')}')"
        else:
            try:
                hint = f" (it reads as {q.units:~P}, a {q.dimensionality})"
            except Exception:
                pass
        raise ModelError(f"{text!r} is not compatible with {unit!r}{hint}") from None


def to_si(value, unit: str) -> float:
    """Return ``value`` as a finite float in the SI ``unit``.

    Numbers are taken as already in ``unit``; strings are parsed with pint ("27 mm",
    "15 N*m", "4 rev/s") and converted. Raises ModelError on an incompatible, malformed or
    non-finite value (NaN, inf, "1e400 m", "1e308 km").
    """
    if isinstance(value, bool):
        raise ModelError(f"expected a number or a quantity in {unit}, got {value!r}")
    if isinstance(value, (int, float)):
        try:
            return finite(float(value), value)
        except OverflowError:  # an int beyond the float range
            raise ModelError(f"must be a finite number, got {value:.3g}") from None
    if isinstance(value, str):
        text = value.strip()
        return finite(_parse(text, unit), repr(value))
    raise ModelError(f"expected a number or a quantity in {unit}, got {value!r}")
