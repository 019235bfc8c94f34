"""Resolve a span model into SI numbers: the span itself, or one span of a belt-drive model.

A span may give ``span.length`` directly, or name a belt-drive model file (``span.belt_model``)
and one of its spans (``span.span_name``, e.g. "driver-driven"): the length then comes from
``drivedyn.mechanics.layout.compute_layout(model).spans``, and the mass per metre, bending stiffness
and pretension default to the belt's when the span model leaves them out. The path is taken
relative to the model file (made absolute at load), then the working directory, then as a
shipped example name.

A span may also name a belt-drive run's ``results.nc`` (``span.belt_results``): the span then comes
from the model text stored in the file, and the pretension and speed default to the span's mean
tension and belt speed in that run's steady window; ``tooth_force.series`` may name the same file
to analyse the span's simulated tension history.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.errors import ModelError
from ..mechanics.span.quantities import SpanProperties


@dataclass(frozen=True)
class Setup:
    """Everything the analysis needs, SI floats.

    Attributes
    ----------
    span : SpanProperties
    pretension, speed : float
        Model's operating point F0 (N) and V (m/s).
    teeth : int
    pitch : float
        Tooth pitch p = 2 pi r / z (m).
    convention : str
        Excitation period convention ("tooth-passing" or "seed").
    """

    span: SpanProperties
    pretension: float
    speed: float
    teeth: int
    pitch: float
    convention: str
    belt_run: "BeltRun | None" = None


@dataclass(frozen=True)
class BeltRun:
    """One span of a belt-drive run, read from its results.nc: the steady window's samples."""

    path: str
    span_name: str
    status: str
    diagnostics: tuple
    window: tuple
    time: np.ndarray
    tension: np.ndarray
    speed: float


def read_belt_run(path: str, span_name: str, field: str = "span.belt_results"):
    """(span length, belt model, BeltRun) of span ``span_name`` of a belt-drive ``results.nc``."""
    import json

    import xarray as xr

    from ..core.model import loads
    from ..core.window import in_window, steady_window

    p = Path(path)
    if not p.exists():
        raise ModelError(f"file {str(p)!r} not found", field=field)
    if not p.is_file():
        raise ModelError(f"{str(p)!r} is not a regular file", field=field)
    try:
        ds = xr.load_dataset(p, engine="h5netcdf")
    except Exception as exc:
        raise ModelError(f"cannot read {str(p)!r} as a drivedyn results file ({type(exc).__name__})", field=field) from None
    if ds.attrs.get("kind") != "belt-drive" or "model_toml" not in ds.attrs or "span_tension" not in ds:
        raise ModelError(f"{str(p)!r} is not the results.nc of a belt-drive run", field=field)
    belt = loads(ds.attrs["model_toml"], source=str(p))
    spans = [str(x) for x in ds["span"].values]
    if span_name not in spans:
        raise ModelError(f"no span named {span_name!r} in {str(p)!r} (has: {', '.join(spans)})", field="span.span_name")
    t = ds["time"].values
    if len(t) < 3:
        raise ModelError(f"{str(p)!r} holds {len(t)} samples: too few for a tension history", field=field)
    # the belt run's own steady window (the same rule as its summary)
    window = steady_window(belt.output.steady_window, float(t[-1]))
    sel = in_window(t, window)
    if sel.sum() < 3:
        window = steady_window(None, float(t[-1]))
        sel = in_window(t, window)
    ten = ds["span_tension"].sel(span=span_name).values[sel]
    speed = abs(float(ds["span_speed"].sel(span=span_name).values[sel].mean()))
    diagnostics = tuple(d.get("code", "") for d in json.loads(ds.attrs.get("diagnostics", "[]")))
    run = BeltRun(str(p), span_name, str(ds.attrs.get("status", "")), diagnostics, window, t[sel], ten, speed)
    from ..mechanics.layout import compute_layout

    length = next(float(sp.length) for sp in compute_layout(belt).spans if sp.name == span_name)
    return length, belt, run


def _belt_model_path(name: str) -> Path:
    p = Path(name)
    if p.exists():
        return p
    from ..core.examples import examples

    shipped = examples().get(p.name.removesuffix(".toml"))
    if shipped is not None:
        return shipped
    raise ModelError(f"belt-drive model {name!r} not found (relative to the working directory, or a shipped example)",
                     field="span.belt_model")


def belt_span(name: str, span_name: str):
    """(span length, belt model) of the span ``span_name`` of the belt-drive model file ``name``."""
    from ..core.model import load

    path = _belt_model_path(name)
    try:
        belt = load(path)
    except ModelError as exc:
        raise ModelError(f"cannot read belt-drive model: {exc}", field="span.belt_model") from None
    if belt.kind != "belt-drive":
        raise ModelError(f"{name!r} is a {belt.kind!r} model, not a belt-drive", field="span.belt_model")
    try:  # imported lazily: the belt-drive analysis is optional for the span analysis
        from ..mechanics.layout import compute_layout
    except ImportError as exc:
        raise ModelError(f"the belt-drive layout is not available in this build ({exc})", field="span.belt_model") from None
    spans = getattr(compute_layout(belt), "spans", None)
    if spans is None:
        raise ModelError("the belt-drive layout gives no spans", field="span.belt_model")
    for sp in spans:
        if getattr(sp, "name", None) == span_name:
            return float(sp.length), belt
    names = ", ".join(str(getattr(sp, "name", "?")) for sp in spans)
    raise ModelError(f"no span named {span_name!r} in {name!r} (has: {names})", field="span.span_name")


def resolve(model) -> Setup:
    """The model's numbers, taking the span from a belt-drive model where asked."""
    s = model.span
    m, EI, F0, source = s.mass_per_length, s.bending_stiffness, model.operation.pretension, "model"
    if s.density is not None:
        m = s.density * s.area
    L = s.length
    belt, run, V = None, None, model.operation.speed
    if s.belt_model is not None:
        L, belt = belt_span(s.belt_model, s.span_name)
        source = f"{s.belt_model}:{s.span_name}"
    elif s.belt_results is not None:
        L, belt, run = read_belt_run(s.belt_results, s.span_name)
        source = f"{s.belt_results}:{s.span_name}"
        # the run's operating point: mean span tension and belt speed in its steady window
        if F0 is None:
            F0 = float(run.tension.mean())
            if not F0 > 0:
                raise ModelError(f"the span's mean tension in the run is {F0:.4g} N: a slack span has no "
                                 "stability chart; give operation.pretension", field="span.belt_results")
        V = run.speed if V is None else V
    if belt is not None:
        m = belt.belt.mass_per_length if m is None else m
        EI = belt.belt.bending_stiffness if EI is None else EI
        if F0 is None:
            if belt.belt.pretension is None:
                raise ModelError("required: the belt-drive model gives no pretension", field="operation.pretension")
            F0 = belt.belt.pretension
    ex = model.excitation
    pitch = ex.pitch if ex.pitch is not None else 2.0 * np.pi * ex.pulley_radius / ex.teeth
    return Setup(SpanProperties(float(L), float(m), float(EI), model.span.damping_ratio, source),
                 float(F0), float(V or 0.0), ex.teeth, float(pitch), ex.period, run)
