"""One results convention for every analysis.

A :class:`Result` wraps an ``xarray.Dataset`` (time series and fields, ``units`` and
``long_name`` in each variable's attrs, the model TOML and versions in the Dataset attrs) and a
nested ``summary`` dict of headline scalars (SI units; key names carry no unit unless they
would be ambiguous, e.g. ``max_overlap_area_mm2``), a ``units`` map (dotted summary key -> unit)
and the run's ``diagnostics`` (see :mod:`drivedyn.core.diagnostics`). ``status`` is one of success,
warning, failed. ``save`` writes ``results.nc`` and ``summary.json``; :func:`open_result` reads
them back.

summary.json: ``{"kind", "status", "message", "diagnostics": [{code, text, quantity, value,
limit, unit}], "units": {"pulleys.driven.speed_mean": "rad/s", ...}, <the summary>}``.
"""
from __future__ import annotations

import fnmatch
import functools
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # xarray (with pandas, 0.3-0.4 s) is imported where a Dataset is made or read
    import xarray as xr

from .._version import __version__
from .diagnostics import Diagnostic, status_of


@dataclass
class Result:
    """Outcome of ``drivedyn.run``.

    Attributes
    ----------
    kind : str
        The analysis kind (``"belt-drive"``, ...).
    ds : xarray.Dataset
        All computed arrays, self-describing (units, model text in attrs).
    summary : dict
        Nested dict of scalars and short lists, JSON-serialisable.
    success : bool
        False when the solve stopped early; ``ds`` then holds what was computed.
    message : str
        Why it stopped, or "" on success.
    diagnostics : list of Diagnostic
        Findings that put the result outside the model's valid regime (status "warning").
    units : dict
        Unit of each dotted summary key ("1" for ratios); keys without a unit are not listed.
    """

    kind: str
    ds: xr.Dataset
    summary: dict = field(default_factory=dict)
    success: bool = True
    message: str = ""
    diagnostics: list = field(default_factory=list)
    units: dict = field(default_factory=dict)

    @property
    def status(self) -> str:
        """"success", "warning" (ran; see ``diagnostics``) or "failed" (stopped; partial results)."""
        return status_of(self.success, self.diagnostics)

    def diagnose(self, code: str, text: str, quantity: str = "", value=None, limit=None, unit: str = "") -> Diagnostic:
        """Add a diagnostic (a code of :data:`drivedyn.core.diagnostics.CODES`) and return it."""
        d = Diagnostic(code, text, quantity, None if value is None else float(value),
                       None if limit is None else float(limit), unit)
        self.diagnostics.append(d)
        return d

    def save(self, outdir) -> Path:
        """Write ``results.nc`` and ``summary.json`` into ``outdir`` (created if needed)."""
        from .outputs import make_folder, replace_write, write_text

        outdir = make_folder(outdir)
        ds = self.ds.copy()
        ds.attrs.update(kind=self.kind, status=self.status, message=self.message, drivedyn_version=__version__,
                        diagnostics=json.dumps([d.to_dict() for d in self.diagnostics]))
        # written by replacing (never through a link planted in the folder); strict JSON: null, not NaN
        replace_write(outdir / "results.nc", lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))
        write_text(outdir / "summary.json", dumps_json(self.summary_document(), indent=2))
        return outdir

    def summary_document(self) -> dict:
        """The summary as written to summary.json (kind, status, message, diagnostics, units first)."""
        doc = {"kind": self.kind, "status": self.status, "message": self.message,
               "diagnostics": [d.to_dict() for d in self.diagnostics], "units": dict(self.units)}
        doc.update(_clean(self.summary))
        return doc

    def flat_summary(self) -> dict:
        """Summary flattened to dotted keys (``pulleys.driver.slip``)."""
        return flatten(self.summary)


def number_text(v: float, unit: str = "") -> str:
    """A summary number as people read it: 6 significant digits, no "-0", rpm beside rad/s."""
    v = v + 0.0
    text = f"{v:.6g}"
    if unit == "rad/s":
        text += f" ({v * 30 / math.pi:.5g} rpm)"
    return text


def open_result(outdir) -> Result:
    """Read a Result written by :meth:`Result.save`."""
    import xarray as xr

    outdir = Path(outdir)
    ds = xr.load_dataset(outdir / "results.nc", engine="h5netcdf")
    doc = json.loads((outdir / "summary.json").read_text())
    kind = doc.pop("kind", ds.attrs.get("kind", ""))
    status = doc.pop("status", "success")
    message = doc.pop("message", "")
    diagnostics = [Diagnostic.from_dict(d) for d in doc.pop("diagnostics", [])]
    units = doc.pop("units", {})
    return Result(kind=kind, ds=ds, summary=doc, success=status != "failed", message=message,
                  diagnostics=diagnostics, units=units)


def unit_map(summary: dict, patterns: dict, rows: bool = False) -> dict:
    """Units of the dotted keys of ``summary`` from ``patterns`` (fnmatch pattern -> unit; the
    first pattern that matches a key wins). ``rows``: the keys of ``flatten(summary, rows=True)``,
    a row's key read against the patterns without its index (the patterns name a table's rows
    as ``supplier.duty.rows.belt_speed``)."""
    rx, units = _pattern_regex(tuple(patterns.items()))
    out = {}
    for key, template in _flat_keys(summary, "", "", rows):
        if rx is not None:
            m = rx.match(template)
            if m:
                out[key] = units[m.lastindex - 1]
            continue
        for pat, unit in patterns.items():
            if fnmatch.fnmatchcase(template, pat):
                out[key] = unit
                break
    return out


@functools.lru_cache(maxsize=32)
def _pattern_regex(items: tuple):
    """One regex of the fnmatch patterns, each its own group in their order (the regex tries the
    alternatives in order, so the first pattern that matches wins), and their units: a run's summary
    has ~200 keys against ~100 patterns."""
    rx = re.compile("|".join(f"({fnmatch.translate(pat)})" for pat, _ in items))
    # (None where fnmatch's translation has groups of its own: then pattern by pattern)
    return (rx if rx.groups == len(items) else None), [unit for _, unit in items]


def flatten(d: dict, prefix: str = "", rows: bool = False) -> dict:
    """``d`` with dotted keys (``pulleys.driver.slip``). ``rows``: a list of tables (a supplier
    report's duty rows) descends too, by index (``supplier.duty.rows.0.belt_speed``), as a study
    collects it; else it is one value."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(flatten(v, key, rows))
        elif rows and _is_rows(v):
            for i, x in enumerate(v):
                out.update(flatten(x, f"{key}.{i}", rows))
        else:
            out[key] = v
    return out


def _is_rows(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _flat_keys(d: dict, prefix: str, template: str, rows: bool):
    """(key, key without its row indices) of ``flatten(d, rows=rows)``, in its order."""
    for k, v in d.items():
        key, tpl = (f"{prefix}.{k}", f"{template}.{k}") if prefix else (str(k), str(k))
        if isinstance(v, dict):
            yield from _flat_keys(v, key, tpl, rows)
        elif rows and _is_rows(v):
            for i, x in enumerate(v):
                yield from _flat_keys(x, f"{key}.{i}", tpl, rows)
        else:
            yield key, tpl


def _clean(obj):
    """JSON-safe copy: numpy scalars to Python, NaN/inf to None."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def _jsonable(obj):
    return _clean(obj)


def dumps_json(obj, **kw) -> str:
    """Strict JSON (RFC 8259) of ``obj``: NaN and infinities become ``null`` (a browser's
    ``JSON.parse`` rejects ``NaN``), numpy scalars plain numbers."""
    return json.dumps(_clean(obj), allow_nan=False, default=_jsonable, **kw)


def variable(data, dims, units: str, long_name: str) -> xr.Variable:
    """Shorthand for a Dataset variable with units and long_name attrs."""
    import xarray as xr

    return xr.Variable(dims, np.asarray(data), attrs={"units": units, "long_name": long_name})
