"""Assembling one xarray Dataset from the case records.

Grid studies get one dimension per parameter; sampled designs a ``case`` dimension with the
parameters as coordinates along it. Each collected summary key becomes a variable named by its
dotted key (``pulleys.driven.slip``; a space as ``_``, the key itself in ``long_name``), NaN where a
case has no value; the rows of a table by index (``supplier.duty.rows.0.belt_speed``); lists of fixed length get an
extra dimension ``<key>.i``. Per case: ``status``, ``message``, ``diagnostics`` (codes),
``case_key`` (the cache key) and ``wall_time``. ``attrs`` hold the study text and the base model text.
"""
from __future__ import annotations

import datetime as _dt
import fnmatch
import json
from pathlib import Path

import numpy as np
import xarray as xr

from .. import __version__
from .cases import STATUSES


def _selected(keys, patterns):
    out = []
    for k in keys:
        if any(fnmatch.fnmatchcase(k, p) for p in patterns) and k not in out:
            out.append(k)
    return out


def near_keys(pattern: str, keys, n: int = 3) -> str:
    """What would match an ``outputs.summary`` pattern that matches none of ``keys``: the keys below
    it (a table's values, ``pulleys.driven.*`` under ``pulleys.driven``), else the closest spellings,
    else the keys under its longest leading part that exists; '' if nothing is near."""
    import difflib

    def listed(found, more=""):
        shown = ", ".join(found[:n]) + (f" and {len(found) - n} more" if len(found) > n else "")
        return shown + more

    below = [k for k in keys if fnmatch.fnmatchcase(k, pattern + ".*")]
    if below:
        return listed(below, f" (keys below it: write {pattern + '.*'!r})")
    close = difflib.get_close_matches(pattern, keys, n=n, cutoff=0.6)
    if close:
        return listed(close)
    parts = pattern.split(".")
    for m in range(len(parts) - 1, 0, -1):
        head = ".".join(parts[:m])
        under = [k for k in keys if k.startswith(head + ".")]
        if under and not any(c in head for c in "*?["):
            return listed(under, f" (under {head!r})")
    return ""


def unmatched_lines(ds) -> list[str]:
    """One line per ``outputs.summary`` pattern that matched no summary key, with what would."""
    near = json.loads(ds.attrs.get("unmatched_near") or "{}")
    pats = near or {p.strip(): "" for p in ds.attrs.get("unmatched_outputs", "").split(",") if p.strip()}
    return [f"outputs.summary: {p!r} matches no summary key" + (f"; near: {hint}" if hint else "")
            for p, hint in pats.items()]


def _kind_of(values):
    """'float', 'str', ('list', n) or None for the non-None values of one summary key."""
    vals = [v for v in values if v is not None]
    if not vals:
        return "float"
    if all(isinstance(v, (bool, int, float)) for v in vals):
        return "float"
    if all(isinstance(v, str) for v in vals):
        return "str"
    if all(isinstance(v, list) for v in vals):
        lens = {len(v) for v in vals}
        if len(lens) == 1 and all(all(isinstance(x, (int, float)) or x is None for x in v) for v in vals):
            return ("list", lens.pop())
    return None


def _safe(name: str) -> str:
    from ..core.outputs import nc_name

    # HDF5 reads "/" as a group separator; names over 200 characters shortened; a space (a position
    # table's "free arm" row) written as "_", so that every variable is one word (long_name keeps the key)
    return nc_name(name.replace(" ", "_"))


def assemble(study, design, cases, records, cache) -> xr.Dataset:
    """The study Dataset from ``records`` (key -> record) in design order."""
    from ..core.model import dumps

    n = len(cases)
    recs = [records.get(c.key) or {"status": "missing", "message": "not run (interrupted?)", "summary": {}}
            for c in cases]
    status = np.array([r["status"] for r in recs], dtype=object)
    keys_seen = []
    for r in recs:
        for k in r.get("summary", {}):
            if k not in keys_seen:
                keys_seen.append(k)
    keys = _selected(keys_seen, study.spec.outputs.summary)
    # patterns that matched no key of any finished case: most likely a typo in the study file
    unmatched = [p for p in study.spec.outputs.summary
                 if keys_seen and not any(fnmatch.fnmatchcase(k, p) for k in keys_seen)]

    data_vars, summary_keys = {}, []
    labels = set(design.labels)
    units = {}      # summary key -> unit, as the cases' results gave it (older cached records have none)
    for r in recs:
        for k, u in (r.get("units") or {}).items():
            units.setdefault(k, u)
    for k in keys:
        vals = [r.get("summary", {}).get(k) for r in recs]
        kind = _kind_of(vals)
        if kind is None:
            continue
        name = _safe(f"summary.{k}" if k in labels or k in ("case", "status", "message", "diagnostics") else k)
        attrs = {"long_name": k, **({"units": units[k]} if k in units else {})}
        if kind == "float":
            arr = np.array([np.nan if v is None else float(v) for v in vals])
            data_vars[name] = (("case",), arr, attrs)
        elif kind == "str":
            arr = np.array(["" if v is None else v for v in vals], dtype=object)
            data_vars[name] = (("case",), arr, attrs)
        else:
            m = kind[1]
            arr = np.array([[np.nan] * m if v is None else [np.nan if x is None else float(x) for x in v] for v in vals])
            data_vars[name] = (("case", _safe(f"{k}.i")), arr, attrs)
        summary_keys.append(name)
    data_vars["status"] = (("case",), status, {"long_name": "case status: " + ", ".join(STATUSES)})
    data_vars["message"] = (("case",), np.array([r.get("message", "") for r in recs], dtype=object),
                            {"long_name": "why the case failed or warned ('' on success)"})
    data_vars["diagnostics"] = (("case",), np.array([",".join(dict.fromkeys(d["code"] for d in r.get("diagnostics", [])))
                                                      for r in recs], dtype=object),
                                {"long_name": "codes of the case's diagnostics, comma-separated ('' if none)"})
    data_vars["case_key"] = (("case",), np.array([c.key for c in cases], dtype=object),
                             {"long_name": "cache key: SHA-256 of the resolved model TOML (first 20 hex digits)"})
    data_vars["wall_time"] = (("case",), np.array([float(r.get("wall_time", np.nan)) for r in recs]),
                              {"units": "s", "long_name": "wall time of the case's run"})
    ds = xr.Dataset(data_vars)
    _add_series(ds, study, cases, recs, cache)

    for p in study.spec.parameters:
        vals = [c.values[p.label] for c in cases]
        ds.coords[p.label] = ("case", np.array(vals, dtype=float if all(isinstance(v, float) for v in vals) else object))
    if design.grid:
        ds = _to_grid(ds, design)
    else:
        ds = ds.assign_coords(case=np.arange(n))
    for p in study.spec.parameters:
        ds[p.label].attrs.update(units=study.units.get(p.label, ""), long_name=", ".join(p.paths),
                                 paths=", ".join(p.paths))
        if p.label in getattr(study, "shown", {}):     # the unit the study file writes it in (shown.py)
            unit, scale = study.shown[p.label]
            ds[p.label].attrs.update(shown_units=unit, shown_scale=scale)
    counts = {s: int((status == s).sum()) for s in STATUSES}
    sp = study.spec
    ds.attrs.update(
        title=study.name, kind="study", base_kind=study.base.kind,
        study_toml=study.text, base_model_toml=dumps(study.base),
        base_model_path=str(study.base_path), sampler=sp.sampler.method,
        samples=len(cases), seed=sp.sampler.seed, parameters=", ".join(design.labels),
        parameter_names=json.dumps(design.labels),    # exact (a name may hold a comma)
        summary_keys="\n".join(summary_keys), series=", ".join(sp.outputs.series),
        unmatched_outputs=", ".join(unmatched),
        unmatched_near=json.dumps({p: near_keys(p, keys_seen) for p in unmatched}),
        drivedyn_version=__version__, created=_dt.datetime.now().isoformat(timespec="seconds"),
        **{f"cases_{s}": v for s, v in counts.items()},
    )
    return ds


def _add_series(ds, study, cases, recs, cache):
    """Stack the requested whole variables of every case along ``case`` (outer join, NaN-filled)."""
    names = study.spec.outputs.series
    if not names:
        return
    parts, idx = [], []
    opened = {}
    for i, (c, r) in enumerate(zip(cases, recs)):
        f = r.get("series_file")
        if not f:
            continue
        if f not in opened:
            path = Path(cache) / f
            opened[f] = xr.load_dataset(path, engine="h5netcdf") if path.exists() else None
        if opened[f] is not None:
            parts.append(opened[f])
            idx.append(i)
    if not parts:
        return
    stacked = xr.concat(parts, dim="case", join="outer", data_vars="all", coords="minimal", compat="override",
                        combine_attrs="drop_conflicts", fill_value=np.nan)
    stacked = stacked.assign_coords(case=idx).reindex(case=np.arange(len(cases)))
    for v in stacked.data_vars:
        name = v if v not in ds.variables else f"series.{v}"
        ds[_safe(name)] = stacked[v]
    for c in stacked.coords:
        if c != "case" and c not in ds.coords:
            ds.coords[c] = stacked[c]


def _to_grid(ds: xr.Dataset, design) -> xr.Dataset:
    """Reshape the ``case`` dimension into one dimension per parameter (C order)."""
    shape = design.shape
    out = xr.Dataset(attrs=ds.attrs)
    for label in design.labels:
        vals = design.axes[label]
        out.coords[label] = (label, np.array(vals, dtype=float if all(isinstance(v, float) for v in vals) else object))
    for name, var in ds.variables.items():
        if name in design.labels or name == "case":
            continue
        if "case" not in var.dims:
            out.coords[name] = var
            continue
        assert var.dims[0] == "case"
        data = np.asarray(var.values).reshape(shape + var.shape[1:])
        target = out.coords if name in ds.coords else out
        target[name] = (tuple(design.labels) + var.dims[1:], data, var.attrs)
    return out


def write_dataset(ds: xr.Dataset, path) -> Path:
    """Write the study netCDF atomically (so a reader never sees half a file)."""
    from ..core.outputs import replace_write

    return replace_write(path, lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))
