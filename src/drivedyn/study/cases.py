"""Cases: resolved models, their cache, and the task a Dask worker runs for one case.

Each case is the base model with the case's overrides applied, validated, and written back to
TOML. The SHA-256 of that text is the case's key: two cases that resolve to the same model share
one run, and a cached result is reused exactly when the model it came from is unchanged.

The cache is a folder of small files per key::

    <key>.json   the record: status, message, flat summary, wall time, worker
    <key>.nc     the requested whole variables (``outputs.series``), if any
    <key>.log    a journal, one line per event (start, end, cached) with host:pid

``<key>.json`` is written last and atomically (temporary file + ``os.replace``), so its presence
means the case is complete. That makes the task idempotent: Dask re-runs the cases of a worker
that died, and a re-run either finds the finished record or computes it again; a half-written
file is never read. Workers write the cache themselves when they can see the folder (local
cluster, shared file system: the ``.study-id`` token proves it is the same folder); otherwise they
return the record and the client writes it.
"""
from __future__ import annotations

import datetime as _dt
import hashlib
import json
import os
import socket
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__
from ..core.errors import ModelError, SolverError, Stopped
from ..core.model import from_dict, set_path, to_dict

TOKEN = ".study-id"
#: statuses a case can end with
STATUSES = ("success", "warning", "failed", "invalid", "error", "lost", "missing")
#: statuses of a case that ran to its end ("warning": with diagnostics; a re-run gives the same)
COMPLETED = ("success", "warning")


@dataclass
class Case:
    """One case of a study.

    Attributes
    ----------
    index : int
        Position in the design (C order for grids).
    values : dict
        Parameter label -> value.
    overrides : dict
        Model path -> value given to :func:`drivedyn.core.model.set_path`.
    toml : str or None
        The resolved model, or None when the overrides do not validate.
    key : str
        Cache key: hash of ``toml`` (or of the overrides when invalid).
    message : str
        The validation error of an invalid case.
    keys : list or None
        The summary keys (patterns) a lean run computes (case_keys), or None: the full run.
    """

    index: int
    values: dict
    overrides: dict
    toml: str | None
    key: str
    message: str = ""
    record: dict = field(default_factory=dict)
    keys: list | None = None


def model_key(toml: str) -> str:
    """Cache key of a resolved model text (first 20 hex digits of its SHA-256)."""
    return hashlib.sha256(toml.encode("utf-8")).hexdigest()[:20]


def case_keys(study) -> list | None:
    """The summary keys (patterns) a design of ``study`` needs, when that is less than its whole
    summary: an optimisation's objective and constraints, unless the study asks for every key
    (``outputs.summary`` given) or for whole variables (``outputs.series``). None: the full run."""
    spec = study.spec
    if spec.mode != "optimise" or spec.eval_mode != "run" or spec.outputs.series:
        return None
    if "summary" in spec.outputs.model_fields_set:
        return None
    opt = spec.optimise
    return [opt.objective] + [c.key for c in opt.constraints]


def resolve(study, design, overrides_of) -> list[Case]:
    """Apply each case's overrides to the base model; invalid combinations are kept, not raised."""
    from ..core.analyses import analysis
    from ..core.model import dumps

    base = to_dict(study.base)
    keys = case_keys(study)
    if keys is not None and not analysis(study.base.kind).lean_possible(study.base, keys):
        keys = None
    out = []
    for i, values in enumerate(design.cases):
        ov = overrides_of(study, values)
        data = json.loads(json.dumps(base))  # deep copy of plain data
        try:
            for path, v in ov.items():
                set_path(data, path, v)
            model = from_dict(data, source="case")
        except ModelError as exc:
            msg = str(exc).removeprefix("case: ")
            key = "invalid-" + hashlib.sha256(json.dumps(ov, sort_keys=True, default=str).encode()).hexdigest()[:12]
            out.append(Case(i, values, ov, None, key, msg))
            continue
        toml = dumps(model)
        # a check of a model is another result than its run, a lean run (the keys named) another
        # than the full run: other cache keys
        mode = study.spec.eval_mode
        lean = keys if keys is not None and analysis(model.kind).lean_possible(model, keys) else None
        head = f"# mode {mode}\n" if mode != "run" else f"# summary {' '.join(lean)}\n" if lean else ""
        out.append(Case(i, values, ov, toml, model_key(head + toml), keys=lean))
    return out


# ---------------------------------------------------------------- the cache, on either side

def _atomic_write(path: Path, data: bytes) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    with open(tmp, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def journal(cache: Path, key: str, event: str) -> None:
    """Append one line to the case's journal (O_APPEND: lines from several processes stay whole)."""
    line = f"{_dt.datetime.now().isoformat(timespec='milliseconds')} {event} {socket.gethostname()}:{os.getpid()}\n"
    fd = os.open(cache / f"{key}.log", os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        os.write(fd, line.encode())
    finally:
        os.close(fd)


def read_record(cache: Path, key: str, series=()) -> dict | None:
    """The finished record of ``key``, or None if absent, unreadable, or lacking requested series."""
    try:
        rec = json.loads((cache / f"{key}.json").read_text())
    except (OSError, ValueError):
        return None
    if set(series) - set(rec.get("series", [])):
        return None  # asked for more whole variables than were kept: run again
    if rec.get("series_file") and not (cache / rec["series_file"]).exists():
        return None
    return rec


def write_record(cache: Path, key: str, record: dict, series_ds=None) -> None:
    """Write a finished case: the series file first, then the record (its presence = done)."""
    record = dict(record)
    record.pop("series_data", None)
    if series_ds is not None and len(series_ds.data_vars):
        tmp = cache / f".{key}.{os.getpid()}.{uuid.uuid4().hex[:8]}.nc.tmp"
        series_ds.to_netcdf(tmp, engine="h5netcdf")
        os.replace(tmp, cache / f"{key}.nc")
        record["series_file"] = f"{key}.nc"
    _atomic_write(cache / f"{key}.json", json.dumps(record, indent=1).encode())


def cache_visible(cache_dir: str, token: str) -> Path | None:
    """The cache folder if this process sees the study's own folder there, else None."""
    try:
        path = Path(cache_dir)
        return path if (path / TOKEN).read_text().strip() == token else None
    except OSError:
        return None


def prune(cache: Path, keep, dry_run=False) -> tuple[int, int]:
    """Remove the cached cases whose key is not in ``keep`` (records, series, journals, stray
    temporary files). Returns (cases removed, bytes freed); ``dry_run`` only counts them."""
    keep = set(keep)
    gone, freed = set(), 0
    for f in cache.iterdir():
        if f.name == TOKEN or not f.is_file():
            continue
        key = f.name.lstrip(".").split(".")[0]
        if key in keep:
            continue
        gone.add(key)
        freed += f.stat().st_size
        if not dry_run:
            f.unlink()
    return len(gone), freed


# ---------------------------------------------------------------- the task

def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def _deadline(timeout):
    """A progress callback that stops the run once ``timeout`` seconds of wall time have passed."""
    if timeout is None:
        return None
    t_end = time.perf_counter() + timeout

    def progress(frac, info=""):
        if time.perf_counter() > t_end:
            raise Stopped(f"case_timeout of {timeout:g} s reached at {100 * frac:.0f} %" + (f" ({info})" if info else ""))
    return progress


def run_case(toml: str, key: str, cache_dir: str, token: str, series: list[str], timeout=None, mode: str = "run",
             keys=None) -> dict:
    """Run one case on a worker and return its record (also written to the cache when visible).

    Every failure of the case itself is caught and recorded, so the task only fails when the
    worker is lost; Dask then runs it again elsewhere. ``timeout`` (s) stops the case at its
    next progress report after that much wall time (status "failed", partial results kept).
    ``keys``: the summary keys (patterns) the study needs, computed by the analysis's lean run
    where it has one (no Dataset, criteria or diagnostics but the solve's; case_keys).
    """
    from ..api import run
    from ..core.model import loads
    from ..core.results import _clean

    cache = cache_visible(cache_dir, token)
    if cache is not None:
        done = read_record(cache, key, series)
        if done is not None:  # finished by an earlier attempt whose worker died before reporting
            journal(cache, key, "cached")
            return done
        journal(cache, key, "start")
    t0 = time.perf_counter()
    status, message, summary, ds, diagnostics, units = "success", "", {}, None, [], {}
    try:
        model = loads(toml, source=f"case {key}")
        if mode == "check":   # what check knows, as the case's summary (no time series)
            import xarray as xr

            from ..core.analyses import analysis
            from ..core.results import Result, unit_map

            a = analysis(model.kind)
            data = a.check_data(model)
            # with its units, so that a constraint's bound is read in them (they were missing: a
            # bound "100 kg" on a tension was read as 100)
            result = Result(model.kind, xr.Dataset(), data, units=unit_map(data, a.summary_units("check")))
        else:
            result = None
            if keys:
                from ..core.analyses import analysis

                result = analysis(model.kind).run_lean(model, keys, progress=_deadline(timeout))
            if result is None:
                result = run(model, progress=_deadline(timeout))
        summary, ds, diagnostics, units = _flat(result, model.kind, mode)
        status, message = result.status, result.message
        if status == "warning":  # the diagnostics, one line
            message = "; ".join(d.line() for d in diagnostics)
    except SolverError as exc:
        status, message = "failed", _one_line(exc)
        if exc.partial is not None:
            summary, ds, diagnostics, units = _flat(exc.partial, model.kind, mode)
    except ModelError as exc:
        status, message = "invalid", _one_line(exc)
    except Stopped as exc:  # an analysis that keeps nothing when stopped
        status, message = "failed", f"stopped: {_one_line(exc)}"
    except Exception as exc:  # a bug in an analysis must not stop the other cases
        status, message = "error", f"{type(exc).__name__}: {_one_line(exc)}"
    record = {
        "key": key, "status": status, "message": message, "summary": _clean(summary),
        "units": {k: u for k, u in units.items() if k in summary},   # the study's plots label axes with them
        "diagnostics": [d.to_dict() for d in diagnostics],
        "wall_time": time.perf_counter() - t0, "worker": f"{socket.gethostname()}:{os.getpid()}",
        "finished": _dt.datetime.now().isoformat(timespec="seconds"), "drivedyn_version": __version__,
        "series": sorted(series),
    }
    sub = None
    if ds is not None and series:
        keep = [v for v in series if v in ds.variables and v not in ds.dims]
        sub = ds[keep].copy()
        sub.attrs = {}
    if cache is not None:
        write_record(cache, key, record, sub)
        journal(cache, key, f"end {status}")
        return read_record(cache, key, series) or record
    record["series_data"] = sub  # the client writes it
    return record


def _flat(result, kind: str, mode: str):
    """(summary, ds, diagnostics, units) of a case's result, its summary flattened with the rows of
    its tables by index (a supplier report's duty rows: ``supplier.duty.rows.0.belt_speed``, which
    a study's outputs.summary collects), their units read from the analysis's tables."""
    from ..core.analyses import analysis
    from ..core.results import flatten, unit_map

    summary = flatten(result.summary, rows=True)
    units = dict(result.units)
    a = analysis(kind)
    patterns = {**a.summary_units(mode), **a.summary_units("check")}
    for k, u in unit_map(result.summary, patterns, rows=True).items():
        units.setdefault(k, u)
    return summary, result.ds, result.diagnostics, units


#: the analyses this process has warmed (warm_worker: once per process, not per batch of cases)
_WARM: set = set()


def warm_worker(kind: str) -> str:
    """Import the analysis on a worker and run its optional ``warmup()`` (numba compilation), once
    per process (an optimisation sends every generation to the same workers)."""
    from ..core.model import analysis

    if kind not in _WARM:
        analysis(kind).warmup()
        _WARM.add(kind)
    return f"{socket.gethostname()}:{os.getpid()}"
