"""Installation values: the span frequencies a tension meter reads at the installation tension,
and the tension a measured span frequency means, from the same belt data.

A sonic or optical tension meter plucks a free span at rest and reads its first transverse
frequency. For a pinned span of length L, mass per metre m, bending stiffness EI at tension T
(mechanics/span/frequencies.py): string f = (1/2L) sqrt(T/m); with bending f = (1/2L) sqrt((T + pi^2 EI/L^2)/m).
The bending correction matters on short spans of stiff belts; the table states it. The band is
the frequency range of the tension tolerance: f is monotonic in T, so the band's ends are the
frequencies at T0 (1 -+ tolerance). Meters want long spans (low, well-separated frequencies and
the smallest share of the bending correction): the longest span is the one to measure.
"""
from __future__ import annotations

from ...core.errors import ModelError
from ...mechanics.span.frequencies import beam_frequency, string_frequency, tension_from_frequency

#: default tension tolerance of an installation (+-10 %: a common belt-maker specification)
TOLERANCE = 0.10


def installation_table(model, tension: float, layout, tolerance: float = TOLERANCE) -> dict:
    """Per span: length, installation tension, string and bending-corrected first frequency,
    the bending correction, the band for ``tension`` (1 -+ tolerance), and which span to measure."""
    m, EI = model.belt.mass_per_length, model.belt.bending_stiffness
    spans = {}
    for sp in layout.spans:
        f_s = float(string_frequency(tension, m, sp.length))
        f_b = float(beam_frequency(tension, m, sp.length, EI))
        spans[sp.name] = {
            "length": float(sp.length), "tension": float(tension),
            "frequency_string": f_s, "frequency": f_b,
            "bending_correction": f_b / f_s - 1.0,
            "band": [float(beam_frequency(tension * (1 - tolerance), m, sp.length, EI)),
                     float(beam_frequency(tension * (1 + tolerance), m, sp.length, EI))],
        }
    longest = max(layout.spans, key=lambda sp: sp.length).name
    return {"tolerance": tolerance, "measure_on": longest, "spans": spans}


def tension_from_span_frequency(model, layout, span_name: str, frequency: float, mode: int = 1) -> float:
    """Installation tension (N) that a frequency measured on span ``span_name`` at rest means,
    with the bending correction (the inverse of the table's frequency)."""
    for sp in layout.spans:
        if sp.name == span_name:
            return float(tension_from_frequency(frequency, model.belt.mass_per_length, sp.length,
                                                model.belt.bending_stiffness, 0.0, mode))
    names = ", ".join(sp.name for sp in layout.spans)
    raise ModelError(f"no span named {span_name!r} (has: {names})", field="span")


def table_lines(table: dict) -> list[str]:
    """The installation table as report lines (check)."""
    tol = 100 * table["tolerance"]
    lines = [f"installation (tension meter on the belt at rest, tension +-{tol:g} %):",
             f"{'span':28s} {'length mm':>10s} {'tension N':>10s} {'f1 Hz':>8s} {'bending %':>9s} "
             f"{'band Hz':>17s}"]
    for name, s in table["spans"].items():
        mark = "  <- measure here" if name == table["measure_on"] else ""
        lines.append(f"{name:28s} {s['length'] * 1e3:10.2f} {s['tension']:10.1f} {s['frequency']:8.1f} "
                     f"{100 * s['bending_correction']:9.2f} {s['band'][0]:8.1f}-{s['band'][1]:<8.1f}{mark}")
    return lines
