"""The ``drivedyn study`` command: a progress bar and a report around :func:`run_study`."""
from __future__ import annotations

import math

from pathlib import Path


def main(study_file, out=None, scheduler=None, workers=None, retry_failed=False, plots=True, quiet=False, report=True,
         dry_run=False, prune=False) -> int:
    """Run a study file with a progress bar (stderr) and print where everything went.

    Returns 0 when every case ran to its end (status success or warning; warned cases are listed),
    1 when some did not (the study still completes).
    ``prune`` removes, after the run, the cached cases that are no longer part of the study.
    Raises :class:`drivedyn.ModelError` on bad input (the command line prints it on one line).
    """
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    import numpy as np

    from ..study.cases import COMPLETED
    from ..study.cases import prune as prune_cache
    from ..study.execute import prepare, run_study

    escape = _escape

    console = Console(stderr=True)
    from ..study.spec import Study, load_study

    study = study_file if isinstance(study_file, Study) else load_study(study_file)
    if study.spec.mode == "optimise":
        return _optimise(study, study_file, out, scheduler, workers, plots, quiet, console, dry_run, report)
    # a dry run resolves only the cases it lists (a large grid is listed in seconds)
    study, design, cases, outdir = prepare(study, out, first=50 if dry_run and not prune else None)
    total = len(design.cases)
    distinct = (f"{len({c.key for c in cases if c.toml is not None})} distinct models" if len(cases) == total
                else "distinct models counted when it runs")
    shape = " x ".join(f"{n} {k}" for k, n in zip(design.labels, design.shape)) if design.grid else f"{total} samples"
    console.print(f"study [bold]{escape(study.name)}[/]: {study.base.kind} model {escape(str(study.base_path))}, "
                  + escape(f"{study.spec.sampler.method} ({shape}) = {total} cases, {distinct}"))
    if dry_run:
        for c in cases[:50]:
            console.print(escape(f"  {c.index:4d} {c.key[:12]}  " + ", ".join(_shown(study, k, v) for k, v in c.values.items()))
                          + (f"  [red]invalid: {escape(c.message)}[/]" if c.toml is None else ""))
        if total > 50:
            console.print(f"  ... and {total - 50} more")
        if prune:
            n, size = prune_cache(outdir / "cases", {c.key for c in cases}, dry_run=True)
            console.print(f"--prune would remove {n} cached case(s) of other models ({size / 1e6:.1f} MB)")
        return 0

    bar = Progress(TextColumn("[bold]cases"), BarColumn(), MofNCompleteColumn(),
                   TextColumn("failed [red]{task.fields[failed]}[/] running [cyan]{task.fields[running]}[/]"),
                   TimeElapsedColumn(), TextColumn("left"), TimeRemainingColumn(), console=console,
                   disable=quiet)
    task = bar.add_task("cases", total=len(cases), failed=0, running=0)

    def progress(c):
        bar.update(task, completed=c["done"], failed=c["not_success"], running=c["running"])

    def on_client(client):
        link = getattr(client, "dashboard_link", None)
        where = client.scheduler.address if getattr(client, "scheduler", None) else "?"
        nw = len(client.scheduler_info().get("workers", {}))
        console.print(f"dask scheduler {where} with {nw} worker(s); dashboard: "
                      + (link if link and _has_dashboard(client) else "none"))

    with bar:
        res = run_study(study, outdir, scheduler=scheduler, workers=workers, retry_failed=retry_failed,
                        plots=plots, progress=progress, on_client=on_client)
    c = res.counts
    from ..study.collect import unmatched_lines

    for line in unmatched_lines(res.ds):
        console.print("[yellow]warning:[/] " + escape(line))
    warned = c.get("warning", 0)
    console.print(f"{c['total']} cases: {c['success']} succeeded, {warned} warned, "
                  f"{c['total'] - c['success'] - warned} did not ({c['ran']} run now, {c['cached']} from the cache)")
    sts = res.ds["status"].values.ravel()
    msgs = res.ds["message"].values.ravel()
    bad = ~np.isin(sts, COMPLETED)
    from ..study.shown import case_names

    names = np.array(case_names(res.ds), dtype=object)
    for label, mask, colour in (("warned", sts == "warning", "yellow"), ("did not finish", bad, "red")):
        for s, m, nm in list(zip(sts[mask], msgs[mask], names[mask]))[:5]:
            console.print(f"  [{colour}]{s}[/]: {escape(str(nm))}: {escape(str(m))}")
        if mask.sum() > 5:
            console.print(f"  ... {mask.sum() - 5} more {label} (see the status, diagnostics and message variables)")
    if prune:
        n, size = prune_cache(outdir / "cases", {c.key for c in cases})
        console.print(f"pruned {n} cached case(s) of other models ({size / 1e6:.1f} MB)")
    console.print(escape(f"wrote {res.path}" + (f" and {len(res.plots)} plot(s) in {Path(res.path).parent / 'plots'}" if res.plots else "")))
    if report:
        from .study_report import write_study_report

        console.print(f"report: {write_study_report(res, study_file, Path(res.path).parent)}")
    return 0 if not bad.any() else 1


def _optimise(study, study_file, out, scheduler, workers, plots, quiet, console, dry_run=False, report=True) -> int:
    """``drivedyn study`` of an optimisation: a progress bar over the budget, then the best design
    (``dry_run``: the design variables, objective and constraints, nothing run)."""
    escape = _escape
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from ..study.execute import run_optimisation
    from ..study.optimise import on_bounds

    if not dry_run:       # the output folder refused before the header, as the grid's (execute.prepare)
        from ..study.execute import _out_folder

        out = _out_folder(study, out)
    opt = study.spec.optimise
    names = ", ".join(p.label for p in study.spec.parameters)
    console.print(escape(f"study {study.name}: {opt.sense} {opt.objective} over {names} "
                         f"({opt.evaluate} per design, at most {opt.budget} designs, differential evolution)"))
    if dry_run:
        for p in study.spec.parameters:
            console.print(escape(f"  {p.label}: {p.range[0]} .. {p.range[1]} ({p.scale}{', integer' if p.integer else ''})"))
        for c in opt.constraints:
            console.print(escape(f"  constraint {c.key}: " + " ".join(f"{k} {v}" for k, v in (("min", c.min), ("max", c.max))
                                                                      if v is not None)))
        return 0
    bar = Progress(TextColumn("[bold]designs"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=console, disable=quiet)
    task = bar.add_task("designs", total=opt.budget)
    with bar:
        res = run_optimisation(study, out, scheduler=scheduler, workers=workers, plots=plots,
                               progress=lambda c: bar.update(task, completed=c["done"]))
    o = res.optimum
    n = len(o.evaluations)
    feasible = sum(1 for e in o.evaluations if e.feasible)
    console.print(f"{n} designs evaluated ({res.counts['ran']} run now, {res.counts['cached']} from the cache), {feasible} feasible")
    hits = on_bounds(study, o.values) if o.values is not None else []
    if report:
        from .study_report import write_optimisation_report

        console.print(escape(f"report: {write_optimisation_report(res, study, study_file, Path(res.path).parent, hits)}"))
    if o.values is None:
        console.print("[red]no feasible design[/]: widen the ranges, loosen the constraints or raise the budget")
        console.print(escape(f"wrote {res.path}"))
        return 1
    from .study_report import study_unit

    console.print(escape(f"best: {opt.objective} = {o.objective:.6g}" + _against_start(o)))
    for k, v in o.values.items():
        unit, scale = study_unit(study, k)
        console.print(escape(f"  {k} = {v * scale:.6g} {unit}".rstrip()) if isinstance(v, float) else escape(f"  {k} = {v}"))
    for h in hits:
        console.print("[yellow]" + escape(f"  {h['name']} sits on the {h['side']} bound of its range ({h['bound']:.6g} "
                                          f"{h['unit']}): the optimum may lie outside it; widen the range") + "[/]")
    for key, c in o.constraints.items():
        bounds = " ".join(f"{side} {c[side]:.4g}" for side in ("min", "max") if side in c)
        if "value" in c:
            console.print(escape(f"  constraint {key}: {c['value']:.4g} ({bounds}, margin {c['margin']:.4g})"))
    sr = getattr(res, "speed_range", None)
    if sr is not None:
        u = f" {sr.unit}" if sr.unit not in ("", "1") else ""
        console.print(escape(f"through the speed range ({sr.rpm[0]:.0f}-{sr.rpm[-1]:.0f} rpm, {len(sr.rpm)} bins), {sr.quantity}: "
                             f"the base file's design {min(sr.base):.4g}-{max(sr.base):.4g}{u}, the best "
                             f"{min(sr.best):.4g}-{max(sr.best):.4g}{u}; better in "
                             f"{sum((b < a) if opt.sense == 'minimise' else (b > a) for a, b in zip(sr.base, sr.best))} "
                             f"of {len(sr.rpm)} bins (the table: report.html)"))
    console.print(escape(f"wrote {res.path}, {Path(res.path).parent / 'best.toml'}"
                         + (f" and {len(res.plots)} plot(s)" if res.plots else "")))
    return 0


def _against_start(o) -> str:
    """'; the base file's design: 206.3 (the best 24 % of it)': the optimum against the design it started from."""
    st = o.start
    if not st or not math.isfinite(st.get("objective", math.nan)):
        return ""
    share = f" (the best {100 * o.objective / st['objective']:.3g} % of it)" if st["objective"] else ""
    return f"; the base file's design: {st['objective']:.6g}{share}" + ("" if st["feasible"] else ", infeasible")


def _shown(study, label, v) -> str:
    """'drive.speed=1000 rpm': a case's value in the unit the study writes it in (plain numbers: as given)."""
    if label in study.shown and isinstance(v, float):
        unit, scale = study.shown[label]
        return f"{label}={v * scale:.6g} {unit}"
    return f"{label}={v}"


def _escape(text) -> str:
    """Text for the terminal: rich markup escaped, every long word shortened (outputs.shorten_words)."""
    from rich.markup import escape

    from ..core.outputs import shorten_words

    return escape(shorten_words(str(text)))


def _has_dashboard(client) -> bool:
    """Whether the scheduler serves a dashboard. A scheduler started apart with ``--no-dashboard``
    still lists its HTTP server (health, metrics) as the service "dashboard", whose /status answers
    404; the dashboard is the Bokeh application attached to that server (distributed's
    ``Scheduler(dashboard=...)``), asked of the scheduler itself."""
    def served(dask_scheduler=None):     # nested: sent by value, the scheduler need not hold drivedyn
        return bool(getattr(getattr(dask_scheduler, "http_application", None), "applications", None))

    try:
        if "dashboard" not in (client.scheduler_info().get("services") or {}):
            return False
        return bool(client.run_on_scheduler(served))
    except Exception:      # the line is cosmetic: never fail a study for it
        return False
