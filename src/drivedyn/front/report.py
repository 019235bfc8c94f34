"""``report.html``: one self-contained page per run (or study) that an engineer opens in a browser
and prints to PDF: status and diagnostics, the headline results with units, every plot embedded
with a caption, and the model's data. Rendered with Jinja2 (templates/report.html.j2); images are
embedded as base64 data, so the file needs no server, no internet and no other file.
"""
from __future__ import annotations

import base64
import datetime as _dt
import math
from pathlib import Path

from .._version import __version__

#: what each standard plot shows (file name -> caption); a plot not listed gets its file name
CAPTIONS = {
    "speeds.png": "Pulley speeds over time (counter-clockwise positive) and the slip of every pulley against the driver.",
    "tensions.png": "Mid-span tension of every span and the hub load of every pulley over time (interval means).",
    "segment_forces.png": "Element, normal and friction force on the tracked belt segments as they travel round the drive (seed 000, figs. 11-13).",
    "energy.png": "Energy balance: work in, energy stored, dissipation by mechanism, and the residual (integration error).",
    "campbell.png": "Campbell diagram: the drive's rotational natural frequencies (linearised, spans EA/L) against the driver's orders.",
    "spectrum.png": "Amplitude spectra over the steady window of the tight span's tension, the pulley speeds and the hub "
                    "loads; the top axis reads frequency as orders of the driver's mean speed, the largest tension peaks "
                    "are named by frequency and order.",
    "belt.png": "The belt at the last frame, segments coloured by their element force.",
    "belt.gif": "The belt moving (segments coloured by element force).",
    "runup.png": "Run-up per crank-speed bin: span tension bands, slip against the crank, order cuts of the tight span, tensioner arm travel.",
    "waterfall.png": "Waterfall: spectrum of the tight span's tension against crank speed; dashed lines are the engine orders.",
    "gears-vibration.png": "Torsional vibration of each gear in the steady window: angle less the nominal rotation, "
                           "with the linear drift removed (its rate in the legend).",
    "gears-kv.png": "Dynamic factor in the steady window: mesh force over its nominal value; dashed: K_v, the largest.",
    "gears-forces.png": "Mesh forces, dynamic transmission error and load sharing between the meshes in the steady window.",
    "gears-spectrum.png": "Mesh-force amplitude per order of the mesh frequency (steady window); dotted: natural frequencies.",
    "gears-sweep.png": "K_v against input speed, simulated and by ISO 6336-1 method B; shaded: speeds where the linear "
                       "model is parametrically unstable (K_v there is meaningless).",
    "gears-campbell.png": "Campbell diagram: natural frequencies against input speed with the mesh-frequency orders; "
                          "circles: resonances.",
    "gears-stiffness.png": "Mesh stiffness over time and over the roll angle (time-varying mesh stiffness, seed 003).",
    "gears-planetary.png": "Planetary stage: static mesh force of each planet (pin position errors included) and the "
                           "stage's natural frequencies with its fixed member held.",
    "span-chart.png": "Stability chart of the span: parametric resonance regions against belt speed (seed 002).",
    "span-floquet.png": "Floquet multipliers of the span: growth (unstable) where the largest exceeds 1.",
    "span-frequencies.png": "First natural frequency of the span against its tension (string, beam, moving beam at the run's speed), "
                            "and the tension a measured frequency gives.",
    "span-response.png": "Transverse response of the span over time.",
    "span-tongue.png": "The principal resonance region (tongue) of the span near the operating point.",
    "span-tooth-force.png": "The tooth-force (tension) excitation of the span.",
    "mesh-interference.png": "Interference of belt teeth and pulley grooves through the engagement (seed 001).",
    "mesh-contours.png": "Tooth and groove contours in the engagement.",
    "mesh-flank-map.png": "Where on the flank the tooth touches the groove.",
    "mesh-maps.png": "Largest overlap area and penetration against the pulley's tooth count and the pitch error "
                     "(colour scale from 0, pale: no overlap).",
    "mesh-comparison.png": "The profile pairs compared, unloaded: largest overlap area and penetration of each pair "
                           "(a pair with none is labelled 0).",
    "mesh-animation.gif": "A tooth entering and leaving the groove.",
    "mesh-load.png": "Under load: the load on each tooth in mesh (tooth 1 next to the tight span) with the load at which it "
                     "would climb out, the cord tension along the wrap, and the jump torque against the installation tension.",
}

def eng(v: float) -> str:
    """A number as an engineer writes it: plain from 1e-3 to 1e6 (6 significant digits, no "-0"),
    beyond in engineering notation, the exponent a multiple of 3 (2.43e5 -> 243e3, 1e-5 -> 10e-6)."""
    v = float(v) + 0.0
    text = f"{v:.6g}"
    if v == 0 or not math.isfinite(v) or (1e-3 <= abs(v) < 1e6 and "e" not in text):
        return "0" if v == 0 else text
    e = 3 * math.floor(math.log10(abs(v)) / 3)
    m = float(f"{v / 10 ** e:.4g}")
    if abs(m) >= 1000:                    # rounding carried into the next group (999.96e3 -> 1e6)
        m, e = m / 1000, e + 3
    return f"{m:g}e{e}"


def _value(v, unit):
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, (int, float)):
        text = eng(v)
        return text + (f" ({v * 30 / math.pi:.5g} rpm)" if unit == "rad/s" else "")
    if isinstance(v, (list, tuple)):
        from .overview import compact

        if any(isinstance(x, (list, tuple, dict)) for x in v):
            return compact(v)
        if len(v) > 8:
            return f"[{len(v)} values: {_value(v[0], '')} ... {_value(v[-1], '')}]"
        return "[" + ", ".join(_value(x, "") for x in v) + "]"
    return str(v)


def _rows(flat: dict, units: dict) -> list[dict]:
    out = []
    for k, v in flat.items():
        unit = units.get(k, "")
        numeric = isinstance(v, (int, float, list, tuple)) and not isinstance(v, bool)
        out.append({"key": k, "value": _value(v, unit if "speed" in k else ""),
                    "unit": "" if unit == "1" or not numeric else unit})
    return out


def _model_rows(model) -> list[dict]:
    from ..core.model import field_unit, to_dict

    rows = []

    def walk(prefix, v, out):
        # dicts by key, lists of tables by index (pulleys.0.radius), other values as they are
        if isinstance(v, dict):
            for k, x in v.items():
                walk(f"{prefix}.{k}" if prefix else str(k), x, out)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                walk(f"{prefix}.{i}", x, out)
        else:
            out[prefix] = v
        return out

    for k, v in walk("", to_dict(model), {}).items():
        try:
            unit = field_unit(type(model), k) or _items_unit(type(model), k)
        except Exception:
            unit = ""
        unit = unit or TABLE_UNITS.get(k.rsplit(".", 1)[-1], "")
        rows.append({"key": k, "value": _value(v, unit), "unit": unit})
    return rows


#: columns of the table fields (the model-file reference), whose schema carries no unit
TABLE_UNITS = {"torque_time": "rows [s, N*m]", "torque_speed": "rows [rad/s, N*m]", "speed_time": "rows [s, rad/s]"}


def _items_unit(model_cls, path) -> str:
    """The unit of a tuple field whose items all carry one (a pulley's centre: (m, m))."""
    import typing

    from ..core.model import schema_at, unwrap

    ann = schema_at(model_cls, path)
    if ann is None:
        return ""
    core = unwrap(ann)[0]
    units = {unwrap(a)[1] for a in typing.get_args(core) if a is not Ellipsis}
    return units.pop() or "" if len(units) == 1 else ""


def _figures(files, captions=None) -> list[dict]:
    out = []
    for f in files:
        f = Path(f)
        if not f.exists() or f.suffix.lower() not in (".png", ".gif"):
            continue
        out.append({"name": f.name, "kind": "png" if f.suffix.lower() == ".png" else "gif",
                    "caption": (captions or {}).get(f.name) or CAPTIONS.get(f.name, f.stem.replace("_", " ")),
                    "data": base64.b64encode(f.read_bytes()).decode("ascii")})
    return out


def render(title, kind, status, message, diagnostics, headline, results, figures, model_rows, model_toml, source="",
           extra="", table=None, model_heading="Model", verdict=None, tables=(), model_note="", supplier=None) -> str:
    from jinja2 import Environment, PackageLoader, select_autoescape

    env = Environment(loader=PackageLoader("drivedyn.front", "templates"), autoescape=select_autoescape(["html", "j2"]))
    return env.get_template("report.html.j2").render(
        title=title, kind=kind, status=status, message=message, diagnostics=diagnostics, headline=headline, results=results,
        figures=figures, model_rows=model_rows, model_toml=model_toml, source=source, extra=extra, table=table,
        model_heading=model_heading, verdict=verdict, tables=list(tables), model_note=model_note, supplier=supplier,
        version=__version__, written=_dt.datetime.now().isoformat(timespec="seconds"))


def write_report(result, outdir, files, model=None, source="") -> Path:
    """Write ``outdir/report.html`` for a run: ``files`` are its plots (embedded)."""
    from ..core.model import dumps, loads

    outdir = Path(outdir)
    if model is None and "model_toml" in result.ds.attrs:
        model = loads(result.ds.attrs["model_toml"])
    from . import supplier_page
    from .overview import tables, verdict_table

    # a drive with a supplier's report: its results and tables first, the dynamics after them
    supplier = None
    if result.kind == "belt-drive" and supplier_page.wanted(result.summary):
        supplier = {"results": supplier_page.results(result.summary),
                    "tables": supplier_page.tables(result.summary, model),
                    "margins": supplier_page.margins_sentence(result.summary)}
    flat = {k: v for k, v in result.flat_summary().items()
            if not (k.startswith(("runup.", "flap.")) and isinstance(v, list))}
    html = render(
        title=(getattr(model, "name", "") or result.kind) if model is not None else result.kind, kind=result.kind,
        status=result.status, message=result.message,
        diagnostics=[_diag(d) for d in result.diagnostics], headline=[],
        results=_rows(flat, result.units), figures=_figures(files),
        model_rows=_model_rows(model) if model is not None else [],
        model_toml=dumps(model) if model is not None else "", source=str(source),
        verdict=verdict_table(result.summary), tables=tables(result, supplier=supplier is None),
        model_note=model_note(result), supplier=supplier)
    from ..core.outputs import write_text

    return write_text(outdir / "report.html", html)


def model_note(result) -> str:
    """Which belt model ran and what it is known to miss (one sentence under the solve's status)."""
    if result.kind != "belt-drive":
        return ""
    s = result.summary
    disc = s.get("discretisation", {})
    if disc.get("model") == "rotational":
        est = disc.get("estimate", {})
        share = est.get("share_of_half_band")
        at_arm = est.get("share_of_half_band_at_a_tensioner", share)
        flap = "" if at_arm == share else f", {at_arm:g} x where a span at a tensioner may take a mode by its flap"
        size = ("" if share is None else
                f"; its span tension extremes may sit {'' if share == 1 else f'{share:g} x '}their half band "
                f"(max - min) / 2 from the segment model's{flap} (discretisation.estimate; its means within 2 %)")
        cells = s.get("belt", {}).get("friction_law") == "elastic-plastic"
        wraps = ("each wrap's belt in cells the rim carries, with their tension and bristles" if cells else
                 "each wrap's belt relaxed to its creep-theory content over one passage")
        return ("Model: the rotational model (one unknown per pulley, rotor and tensioner; the spans as axial springs; "
                f"{wraps}). Not in it: the spans' transverse motion (flap, judged from its frequencies; in the "
                f"segment model a span at a tensioner splits the arm's mode as a tuned absorber would) and the belt's "
                f"axial waves{size}. Confirm a design with simulation.model = \"segments\".")
    n = s.get("belt", {}).get("segments") or disc.get("segments")
    if n:
        law = s.get("belt", {}).get("friction_law", "")
        return (f"Model: the segment model (after Kubas, Archiwum Motoryzacji 67 (2015): {n} rigid belt segments in the plane, penalty contact, "
                f"{law} friction). Not in it: the belt's motion out of the drive's plane and polygon effects "
                "beyond the discretisation estimate (discretisation.estimate).")
    return ""


def _diag(d) -> dict:
    e = d.to_dict()
    unit = e.get("unit") or ""
    e["unit"] = "" if unit in ("", "1") else f" {unit}"
    for k in ("value", "limit"):
        if isinstance(e.get(k), float):
            e[k] = eng(e[k])
    return e
