"""Running a study on dask.distributed: a local cluster by default, any scheduler by address.

The flow: resolve every case and hash it; look each key up in the cache; submit only what is
missing (one task per distinct model, ``pure=False`` so nothing is taken from Dask's own memory);
write each record as it arrives; assemble the Dataset from the cache at the end, also after an
interruption. A lost worker's tasks are re-run by the scheduler (``distributed.scheduler.
allowed-failures``); a task that exhausts those retries is recorded as ``lost`` and, not being
cached, runs again on the next resume.
"""
from __future__ import annotations

import contextlib
import os
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from ..core.errors import ModelError
from .cases import COMPLETED, STATUSES, TOKEN, Case, read_record, resolve, run_case, warm_worker, write_record
from .design import make_design, overrides_of
from .spec import Study, load_study


@dataclass
class StudyRun:
    """What :func:`run_study` did.

    Attributes
    ----------
    ds : xarray.Dataset
        The study Dataset (also written to ``path``).
    path : pathlib.Path
        The netCDF file written (``<out>/study.nc``).
    counts : dict
        ``total`` cases, ``ran`` (distinct models executed now), ``cached`` (cases reused from the
        cache), and one count per status (``success``, ``warning``, ``failed``, ``invalid``,
        ``error``, ``lost``, ``missing``).
    plots : list of pathlib.Path
        The PNG files written.
    """

    ds: object
    path: Path
    counts: dict
    plots: list = field(default_factory=list)


def default_workers() -> int:
    """One worker per usable core (single-threaded: the kernels hold the GIL)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:
        return max(1, os.cpu_count() or 1)


def _local_cluster(workers):
    import logging
    import signal
    import threading

    from distributed import LocalCluster

    # Ctrl-C reaches every process of the terminal's foreground group: the workers, started here with
    # SIGINT ignored (inherited through exec; Python leaves an ignored SIGINT alone), stay up for the
    # client to stop them, rather than each dying with its own CommClosedError tracebacks
    main = threading.current_thread() is threading.main_thread()
    old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        # ":0": a free port, so two studies (or a notebook's cluster) never fight over 8787. Dask's own
        # log lines silenced below CRITICAL: a case records its own failure (cases.run_case), a lost
        # worker is the case's status "lost", and a worker stopped mid-case (Ctrl-C) logs its
        # heartbeat's CommClosedError tracebacks, which say nothing to the study's user
        return LocalCluster(n_workers=workers or default_workers(), threads_per_worker=1, processes=True,
                            dashboard_address=":0", silence_logs=logging.CRITICAL)
    finally:
        if main:
            signal.signal(signal.SIGINT, old)


@contextlib.contextmanager
def _quiet_logs():
    """Dask's loggers silenced for the block (after Ctrl-C: the cancelled tasks' and closed
    connections' lines say nothing the interruption's one line does not)."""
    import logging

    quiet = [logging.getLogger(n) for n in ("distributed", "tornado", "asyncio")]
    levels = [lg.level for lg in quiet]
    for lg in quiet:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for lg, lv in zip(quiet, levels):
            lg.setLevel(lv)


def _close(client, cluster, interrupted: bool) -> None:
    """Close the client and the cluster made here; after Ctrl-C quietly, whatever the closing meets."""
    with _quiet_logs() if interrupted else contextlib.nullcontext():
        for part in (client, cluster):
            if part is None:
                continue
            try:
                part.close()
            except Exception:
                if not interrupted:
                    raise


def _executing(prefix):
    """Number of this study's tasks executing right now (runs on the scheduler)."""
    def count(dask_scheduler=None):
        return sum(1 for ws in dask_scheduler.workers.values() for ts in ws.executing
                   if str(ts.key).startswith(prefix))
    return count


def prepare(study, out, first=None):
    """Load, design and resolve a study; create its output folders. Returns (study, design, cases, out).

    ``first``: resolve only that many cases and create nothing (a dry run lists a large grid in
    seconds: validating a case costs about a millisecond)."""
    if not isinstance(study, Study):
        study = load_study(study)
    design = make_design(study)
    if first is not None:
        from dataclasses import replace as _replace

        cases = resolve(study, _replace(design, cases=design.cases[:first]), overrides_of)
        return study, design, cases, Path(out) if out is not None else study.default_out()
    out = _out_folder(study, out)
    cases = resolve(study, design, overrides_of)
    return study, design, cases, out


def _out_folder(study, out) -> Path:
    """The study's output folder with its case cache, checked writable (one line if not)."""
    from ..core.outputs import OutputError, check_folder

    out = Path(out) if out is not None else study.default_out()
    cache = out / "cases"
    try:     # the up-front check of the output folder: one line before any case runs
        check_folder(out, "the study's output folder")
        check_folder(cache, "the study's output folder")
        if not (cache / TOKEN).exists():
            (cache / TOKEN).write_text(uuid.uuid4().hex)
    except OutputError as exc:
        raise ModelError(str(exc)) from None
    except OSError as exc:
        raise ModelError(f"{out}: cannot write the study's output folder ({exc.strerror or exc})") from None
    return out


def run_study(study, out=None, *, client=None, scheduler=None, workers=None, retry_failed=False,
              plots=True, progress=None, on_client=None) -> StudyRun:
    """Run a parameter study and return its Dataset.

    Parameters
    ----------
    study : str, pathlib.Path or Study
        The study file (or a loaded study).
    out : path, optional
        Output folder; default: the study's ``out``, else the study file's stem.
        Gets ``study.nc``, ``cases/`` (the cache) and ``plots/``.
    client : distributed.Client, optional
        Use this client (its cluster is left running).
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:8786``); otherwise a LocalCluster is started
        with ``workers`` single-threaded worker processes (default: one per core).
    retry_failed : bool
        Also re-run cases cached as failed/invalid/error (by default only missing or changed
        cases run; a case cached as "warning" ran to its end and is never re-run).
    plots : bool
        Draw the study plots into ``<out>/plots``.
    progress : callable, optional
        ``progress(counts)`` with keys total, done, not_success, running, cached, ran; called as
        it goes.
    on_client : callable, optional
        ``on_client(client)`` once the client is up (e.g. to print the dashboard address).

    Returns
    -------
    StudyRun
    """
    from .collect import assemble, write_dataset

    study, design, cases, out = prepare(study, out)
    cache = out / "cases"
    series = list(study.spec.outputs.series)
    records: dict[str, dict] = {}
    todo = _to_run(cases, cache, series, records, retry_failed)
    cached = sum(1 for c in cases if c.toml is not None and c.key in records)
    counts = {"total": len(cases), "cases_to_run": len(todo), "cached": cached, "done": len(cases) - len(_pending(cases, todo)),
              "not_success": sum(1 for c in cases if c.key in records and records[c.key]["status"] not in COMPLETED),
              "running": 0, "ran": 0}
    if progress:
        progress(dict(counts))
    interrupted = None
    if todo:
        try:
            _execute(study, todo, cases, cache, series, records, counts, client, scheduler, workers, progress, on_client)
        except KeyboardInterrupt as exc:  # keep what finished; the rest stays "missing"
            interrupted = exc
    ds = assemble(study, design, cases, records, cache)
    path = write_dataset(ds, out / "study.nc")      # OutputError (one line) if the folder changed meanwhile
    for s in STATUSES:
        counts[s] = int((ds["status"].values == s).sum())
    files = []
    if plots and study.spec.plots.enabled and interrupted is None:
        from .plots import plot_study

        files = plot_study(ds, out / "plots", keys=_plot_keys(study, ds))
    if interrupted is not None:
        raise interrupted
    return StudyRun(ds, path, counts, files)


def run_optimisation(study, out=None, *, client=None, scheduler=None, workers=None, plots=True, progress=None,
                     on_client=None) -> StudyRun:
    """Run a study with ``mode = "optimise"`` (optimise.py): every generation of designs one batch
    of cases on one cluster; writes study.nc (every design evaluated, with its objective, feasibility
    and generation), best.toml (the best feasible design as a model file) and plots/optimise.png.
    The StudyRun carries ``optimum`` (optimise.Optimum)."""
    import numpy as np

    from .collect import assemble, write_dataset
    from .design import Design
    from .optimise import plot_convergence, plot_speed_range, run_optimise, speed_range

    if not isinstance(study, Study):
        study = load_study(study)
    out = _out_folder(study, out)
    cache = out / "cases"
    series = list(study.spec.outputs.series)
    records: dict[str, dict] = {}
    counts = {"total": study.spec.optimise.budget, "cases_to_run": 0, "cached": 0, "done": 0, "not_success": 0,
              "running": 0, "ran": 0}
    client, own_client, own_cluster = _client(client, scheduler, workers)
    if on_client:
        on_client(client)

    evaluated = [0]

    def execute(cases, probe=False):
        known = len(records)
        # a design cached as not finished runs again (its generation needs a score)
        todo = _to_run(cases, cache, series, records, retry_failed=True)
        counts["cached"] += len(records) - known
        if todo:
            _execute(study, todo, cases, cache, series, records, counts, client, None, None, None, None)
        if probe:        # a design ahead of its generation: counted with the generation
            return records
        evaluated[0] += len(cases)
        counts["done"] = evaluated[0]
        if progress:
            progress(dict(counts, running=0))
        return records

    interrupted = False
    try:
        optimum = run_optimise(study, execute)
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        _close(own_client, own_cluster, interrupted)
    evals = optimum.evaluations
    cases = [e.case for e in evals]
    design = Design([p.label for p in study.spec.parameters], False, {}, [c.values for c in cases])
    ds = assemble(study, design, cases, records, cache)
    ds["objective"] = ("case", np.array([e.objective for e in evals]),
                       {"long_name": f"objective: {study.spec.optimise.objective} (nan: infeasible)"})
    ds["feasible"] = ("case", np.array([e.feasible for e in evals]),
                      {"long_name": "the design met every constraint and ran to its end"})
    ds["generation"] = ("case", np.array([e.generation for e in evals]),
                        {"long_name": "generation of differential evolution"})
    ds.attrs.update(optimise_objective=study.spec.optimise.objective, optimise_sense=study.spec.optimise.sense,
                    optimise_best=float(optimum.objective) if optimum.values else float("nan"))
    path = write_dataset(ds, out / "study.nc")
    if optimum.toml is not None:
        from ..core.outputs import write_text

        write_text(out / "best.toml", f"# the best feasible design of {study.name or 'the study'}: objective "
                   f"{study.spec.optimise.objective} = {optimum.objective:.6g}\n" + optimum.toml)
    for s in STATUSES:
        counts[s] = int((ds["status"].values == s).sum())
    counts["total"] = len(cases)
    files = []
    # a run-up objective: the base file's design and the best through the speed range (two more runs)
    sr = speed_range(optimum, study.spec.optimise.objective) if study.spec.optimise.evaluate == "run" else None
    if plots and study.spec.plots.enabled:
        (out / "plots").mkdir(exist_ok=True)
        unit = next((r.get("units", {}).get(study.spec.optimise.objective, "") for r in records.values()), "")
        files.append(plot_convergence(optimum, out / "plots" / "optimise.png", study.spec.optimise.objective,
                                      study.spec.optimise.sense, unit))
        if sr is not None:
            files.append(plot_speed_range(sr, out / "plots" / "speed_range.png"))
    run = StudyRun(ds, path, counts, files)
    run.optimum = optimum
    run.speed_range = sr
    return run


def _to_run(cases, cache, series, records, retry_failed) -> dict[str, Case]:
    """The distinct cases to run (key -> case): those neither in ``records`` nor in the cache (nor
    cached as not finished, with ``retry_failed``). Cached records and invalid cases' records go
    into ``records``."""
    todo: dict[str, Case] = {}
    for c in cases:
        if c.toml is None:
            records[c.key] = {"key": c.key, "status": "invalid", "message": c.message, "summary": {}}
            continue
        if c.key in records or c.key in todo:
            continue
        rec = read_record(cache, c.key, series)
        if rec is not None and (rec["status"] in COMPLETED or not retry_failed):
            records[c.key] = rec
        else:
            todo[c.key] = c
    return todo


def _pending(cases, todo):
    return [c for c in cases if c.key in todo]


def _plot_keys(study, ds):
    if study.spec.plots.keys is not None:
        return study.spec.plots.keys
    outs = study.spec.outputs.summary
    if outs == ["*"]:
        return []  # everything collected would be dozens of plots: plot only what was asked for
    return [v for v in ds.attrs.get("summary_keys", "").split("\n") if v]


def _client(client, scheduler, workers):
    """(client, the client if made here, the local cluster if made here): the given client, one
    connected to ``scheduler``, or a local cluster of ``workers`` processes."""
    from distributed import Client

    if client is not None:
        return client, None, None
    if scheduler:
        try:
            c = Client(scheduler, timeout="20s")
        except OSError as exc:
            raise ModelError(f"--scheduler {scheduler}: cannot connect: {exc}") from None
        return c, c, None
    cluster = _local_cluster(workers)
    c = Client(cluster)
    return c, c, cluster


def _execute(study, todo, cases, cache, series, records, counts, client, scheduler, workers, progress, on_client):
    client, own_client, own_cluster = _client(client, scheduler, workers)
    interrupted = False
    try:
        if on_client:
            on_client(client)
        client.run(warm_worker, study.base.kind)
        prefix = f"drivedyn-case-{uuid.uuid4().hex[:8]}-"
        cache_dir, token = str(cache.resolve()), (cache / TOKEN).read_text().strip()
        futures = {client.submit(run_case, c.toml, k, cache_dir, token, series, study.spec.case_timeout, study.spec.eval_mode,
                                 c.keys, key=prefix + k, pure=False): k
                   for k, c in todo.items()}
        weight = {k: sum(1 for c in cases if c.key == k) for k in todo}  # duplicated cases share a run
        count_running = _executing(prefix)
        last_poll = 0.0
        try:
            while futures:
                finished = [f for f in futures if f.done()]
                for f in finished:
                    k = futures.pop(f)
                    rec = _collect_one(f, k, cache, todo[k].toml)
                    records[k] = rec
                    counts["done"] += weight[k]
                    counts["ran"] += 1
                    if rec["status"] not in COMPLETED:
                        counts["not_success"] += weight[k]
                    f.release()
                now = time.monotonic()
                if progress and (finished or now - last_poll > 0.5):
                    if now - last_poll > 0.5:
                        try:
                            counts["running"] = client.run_on_scheduler(count_running)
                        except Exception:  # the count is cosmetic: never fail a study for it
                            pass
                        last_poll = now
                    progress(dict(counts))
                if futures and not finished:
                    time.sleep(0.1)
        except KeyboardInterrupt:
            interrupted = True
            with _quiet_logs():
                for f in futures:
                    f.cancel()
            raise
        finally:
            for f in futures:
                f.cancel()
        counts["running"] = 0
        if progress:
            progress(dict(counts))
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        _close(own_client, own_cluster, interrupted)


def _collect_one(future, key, cache, toml):
    """Record of a finished future; written to the cache by the client if the worker could not."""
    if future.status == "error":
        exc = future.exception()
        first = str(exc).splitlines()[0] if str(exc) else ""
        # the task catches every failure of the case, so this is Dask's: a worker lost too often
        # (KilledWorker), or the task could not even start there (drivedyn missing on a worker)
        status = "lost" if type(exc).__name__ == "KilledWorker" else "error"
        return {"key": key, "status": status, "message": f"{type(exc).__name__}: {first}", "summary": {}}
    if future.status == "cancelled":
        return {"key": key, "status": "missing", "message": "cancelled", "summary": {}}
    rec = future.result()
    if "series_data" in rec:  # the worker could not see the cache folder
        sub = rec.pop("series_data")
        write_record(cache, key, rec, sub)
        rec = read_record(cache, key, rec.get("series", [])) or rec
    return rec
