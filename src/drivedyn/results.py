"""One results convention for every analysis.

A :class:`Result` wraps an ``xarray.Dataset`` (time series and fields, ``units`` and
``long_name`` in each variable's attrs, the model TOML and versions in the Dataset attrs) and a
nested ``summary`` dict of headline scalars (SI units; key names carry no unit unless they
would be ambiguous, e.g. ``max_overlap_area_mm2``). ``save`` writes ``results.nc`` and
``summary.json``; :func:`open_result` reads them back.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from . import __version__


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
    """

    kind: str
    ds: xr.Dataset
    summary: dict = field(default_factory=dict)
    success: bool = True
    message: str = ""

    def save(self, outdir) -> Path:
        """Write ``results.nc`` and ``summary.json`` into ``outdir`` (created if needed)."""
        outdir = Path(outdir)
        outdir.mkdir(parents=True, exist_ok=True)
        ds = self.ds.copy()
        ds.attrs.update(kind=self.kind, status="success" if self.success else "failed",
                        message=self.message, drivedyn_version=__version__)
        ds.to_netcdf(outdir / "results.nc", engine="h5netcdf")
        (outdir / "summary.json").write_text(json.dumps(self.summary_document(), indent=2, default=_jsonable))
        return outdir

    def summary_document(self) -> dict:
        """The summary as written to summary.json (with kind, status and message)."""
        doc = {"kind": self.kind, "status": "success" if self.success else "failed", "message": self.message}
        doc.update(_clean(self.summary))
        return doc

    def flat_summary(self) -> dict:
        """Summary flattened to dotted keys (``pulleys.driver.slip``)."""
        return flatten(self.summary)


def open_result(outdir) -> Result:
    """Read a Result written by :meth:`Result.save`."""
    outdir = Path(outdir)
    ds = xr.load_dataset(outdir / "results.nc", engine="h5netcdf")
    doc = json.loads((outdir / "summary.json").read_text())
    kind = doc.pop("kind", ds.attrs.get("kind", ""))
    status = doc.pop("status", "success")
    message = doc.pop("message", "")
    return Result(kind=kind, ds=ds, summary=doc, success=status == "success", message=message)


def flatten(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(flatten(v, key))
        else:
            out[key] = v
    return out


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


def variable(data, dims, units: str, long_name: str) -> xr.Variable:
    """Shorthand for a Dataset variable with units and long_name attrs."""
    return xr.Variable(dims, np.asarray(data), attrs={"units": units, "long_name": long_name})
