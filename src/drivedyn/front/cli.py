"""The ``drivedyn`` command: a thin layer over drivedyn.run / check / plot / study.

Every user mistake ends with one line on stderr and exit status 2; a failed solve writes what
was computed, says where it stopped, and exits with status 1. A run that ends with diagnostics
(status "warning") prints them and exits with 0, or with 3 under ``--strict``.
"""
from __future__ import annotations

import shutil
import sys
from pathlib import Path
from typing import Optional

import typer

from ..core.errors import DrivedynError, ModelError, SolverError

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Dynamics and geometry of belt drives and gear trains.")


#: exit status of a run that ended with status "warning" under --strict
EXIT_WARNING = 3
#: exit status of a run whose verdict is "fail" (a design criterion failed) under --strict
EXIT_CRITERIA = 4


def _fail(message: str, code: int = 2):
    typer.echo(f"drivedyn: error: {message}", err=True)
    raise typer.Exit(code)


def _named(path: Path, exc: Exception) -> str:
    """The error's message, prefixed with the model file unless it already names it."""
    text = str(exc)
    return text if text.startswith(str(path)) else f"{path}: {text}"


def check_outdir(out: Path) -> None:
    """Refuse an output folder that cannot be written, before any solve (one line, exit 2)."""
    from ..core.outputs import OutputError, check_folder

    try:
        check_folder(out)
    except OutputError as exc:
        _fail(str(exc))


def _write_failed(out: Path, exc: OSError, since: float):
    """A write that failed after the up-front check: one line, the run failed (exit 1), what was
    written kept and named."""
    from ..core.outputs import OutputError

    text = str(exc) if isinstance(exc, OutputError) else f"cannot write into {out}: {exc.strerror or exc}"
    try:
        kept = sorted(p.name for p in out.iterdir() if p.is_file() and not p.name.startswith(".")
                      and not p.is_symlink() and p.stat().st_mtime >= since - 1)
    except OSError:
        kept = []
    _fail(f"writing the outputs failed: {text}; written: {', '.join(kept) if kept else 'nothing'}", code=1)


def _progress_bar(console):
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    return Progress(TextColumn("[bold]{task.description}"), BarColumn(), TextColumn("{task.percentage:>5.1f}%"),
                    TimeElapsedColumn(), TimeRemainingColumn(), TextColumn("{task.fields[info]}"),
                    console=console, transient=False)


SET_HELP = ("Change one value of the model, KEY=VALUE (repeatable): a dotted path and a TOML value, "
            "e.g. --set simulation.model=rotational --set belt.pretension='\"600 N\"'.")


def _load(model: Path, sets: list[str] | None):
    """The model file, with the --set changes applied (one line and exit 2 on a bad one)."""
    import tomllib

    from .. import replace
    from ..core.model import load

    try:
        m = load(model)
        if not sets:
            return m
        changes = {}
        for item in sets:
            key, eq, text = item.partition("=")
            if not eq or not key.strip():
                raise ModelError(f"--set {item!r}: give KEY=VALUE, e.g. simulation.model=rotational")
            try:
                value = tomllib.loads(f"v = {text.strip()}")["v"]
            except tomllib.TOMLDecodeError:
                value = text.strip()          # a bare word: the string itself
            changes[key.strip()] = value
        return replace(m, changes)
    except ModelError as exc:
        _fail(_named(model, exc))


#: seconds before the progress bar shows without a report (assembling a drive takes up to about 2 s;
#: a first run then compiles the kernels, minutes, and the bar says so)
BAR_DELAY = 3.0


class _LazyBar:
    """A progress bar that starts at the first report or after BAR_DELAY, whichever comes first."""

    def __init__(self, bar, kind: str):
        import threading

        self.bar, self.kind, self.task = bar, kind, None
        self.lock = threading.Lock()
        self.timer = threading.Timer(BAR_DELAY, self._start)
        self.timer.daemon = True
        self.timer.start()

    def _start(self):
        with self.lock:
            if self.task is None:
                self.bar.start()
                # until the first report: numba compiles the kernels on their first use only
                self.task = self.bar.add_task(self.kind, total=1.0,
                                              info="preparing (a first run compiles the kernels: up to a minute)")

    def update(self, frac, info=""):
        self._start()
        self.bar.update(self.task, completed=min(max(frac, 0.0), 1.0), info=info)

    def close(self):
        self.timer.cancel()
        with self.lock:
            if self.task is not None:
                self.bar.stop()


@app.command()
def run(model: Path = typer.Argument(..., help="Model file (TOML)."),
        out: Path = typer.Option(Path("out"), "-o", "--out", help="Output folder."),
        plots: bool = typer.Option(True, help="Write the standard PNG plots."),
        report: bool = typer.Option(True, help="Write report.html (one page: status, results, plots, model)."),
        quiet: bool = typer.Option(False, "-q", "--quiet", help="No progress bar."),
        strict: bool = typer.Option(False, "--strict", help=f"Exit with status {EXIT_WARNING} when the run ends "
                                    f"with diagnostics (status 'warning'), {EXIT_CRITERIA} when a design criterion fails."),
        show_all: bool = typer.Option(False, "--all", help="Also print the full summary (every value of summary.json)."),
        sets: list[str] = typer.Option(None, "--set", help=SET_HELP),
        ):
    """Run a model; write results.nc, summary.json, plots and report.html into OUT."""
    from rich.console import Console

    from .. import api

    console = Console(stderr=True)      # progress and errors
    results = Console()                 # what the run found: `drivedyn run m.toml > log.txt` keeps it
    m = _load(model, sets)
    check_outdir(out)
    import time

    started = time.time()
    result, failure = None, None
    import contextlib

    # processes that import the plotting libraries while the model is solved, then write results.nc
    # and the plots (before the progress bar: it runs a thread, and they are forked)
    painters = api.painters(m.kind, m) if plots else None
    with contextlib.ExitStack() as stack:
        if painters is not None:
            stack.enter_context(painters)
        # the bar appears at the first progress report, or after BAR_DELAY: a refusal found while the
        # drive is assembled (milliseconds) is then the only line printed. xarray (a run's results,
        # 0.3-0.5 s, no longer imported with drivedyn) is imported first, not inside that delay
        import xarray  # noqa: F401

        bar = None if quiet else _LazyBar(_progress_bar(console), m.kind)
        refused = None
        try:
            result = api.run(m, progress=None if quiet else bar.update)
        except SolverError as exc:
            failure = exc
            result = exc.partial
        except ModelError as exc:
            refused = exc           # said once the bar is gone, so that the error is the last line
        finally:
            if bar is not None:
                bar.close()
        if refused is not None:
            _fail(_named(model, refused))
        if result is not None:
            if not quiet:
                console.print(f"writing results.nc and summary.json{', plots' if plots else ''}"
                              f"{' and report.html' if report else ''} into {out} ...")
            try:
                if plots and painters is not None:     # one painter writes results.nc, the others start drawing
                    from ..core.plotting import save_result

                    saved = painters.submit(result, save_result, out)
                    written = api.plot(result, out, painters=painters)
                    saved.result()
                elif plots:     # results.nc is written while the figures are drawn
                    written = api.plot(result, out, meanwhile=lambda: result.save(out))
                else:
                    result.save(out)
                    written = []
            except OSError as exc:      # after the up-front check: permissions changed, disk full, ...
                _write_failed(out, exc, started)
    if result is not None:
        results.print(f"wrote {out / 'results.nc'}, {out / 'summary.json'} and {len(written)} plot(s)")
        if report:
            from .report import write_report

            try:
                results.print(f"report: {write_report(result, out, written, model=m, source=model)}")
            except OSError as exc:
                _write_failed(out, exc, started)
        _print_overview(results, result)
        if show_all:
            _print_summary(results, result)
        _print_status(results, result)
    if failure is not None:
        _fail(f"solve failed: {failure}" + ("; partial results kept in " + str(out) if result is not None else ""), code=1)
    if strict and result is not None and result.status == "warning":
        raise typer.Exit(EXIT_WARNING)
    if strict and result is not None and result.summary.get("verdict") == "fail":
        raise typer.Exit(EXIT_CRITERIA)


#: the widest a table is printed to a file or a pipe (columns of names whole, a long cell folded)
PIPE_WIDTH = 180


def _print_table(console, table):
    """A table that fits the terminal (rich folds its cells), or, written to a file or a pipe,
    keeps its columns whole at whatever width they need."""
    if console.is_terminal:
        console.print(table)
    else:
        # measured, and printed, beyond the console's own width (80 on a pipe), which bounds both
        # (print's width is clamped to it); a long text cell (a verdict's where) folds at PIPE_WIDTH
        wide = min(PIPE_WIDTH, console.measure(table, options=console.options.update_width(100_000)).maximum)
        narrow = console.width
        console.width = max(narrow, wide)
        try:
            console.print(table, crop=False)
        finally:
            console.width = narrow


def _text(text) -> str:
    """Text for the terminal: rich markup escaped, every long word shortened (names are data: the
    terminal library folds one long word in quadratic time; outputs.shorten_words)."""
    from rich.markup import escape

    from ..core.outputs import shorten_words

    return escape(shorten_words(str(text)))


def _print_overview(console, result):
    """The verdict table, then the tables per object (overview.py); the full summary is --all."""
    from rich.table import Table

    from .overview import tables, verdict_table

    v = verdict_table(result.summary)
    style = {"pass": "green", "fail": "red"}.get(v["verdict"], "yellow")
    if v["rows"]:
        t = Table(title=f"verdict: [{style}]{v['verdict']}[/{style}]", title_justify="left")
        for h in v["head"][:-1]:
            t.add_column(h, justify="right" if h in ("value", "limit") else "left", overflow="fold")
        for r in v["rows"]:
            cells = [_text(str(c)) for c in r[:-1]]
            cells[4] = f"[green]{cells[4]}[/green]" if r[4] == "pass" else f"[red]{cells[4]}[/red]"
            t.add_row(*cells)
        _print_table(console, t)
        # what each criterion judges (span_tension is the tension less m v^2, not a span's minimum)
        for r in v["rows"]:
            if r[6]:
                console.print(_text(f"  {r[0]}: {r[6]}"), style="dim", soft_wrap=not console.is_terminal)
    else:
        console.print(f"verdict: [{style}]{v['verdict']}[/{style}]")
    if v["note"]:
        console.print(_text(f"not judged: {v['note']}"), soft_wrap=not console.is_terminal)
    from .supplier_page import margins_sentence

    said = margins_sentence(result.summary)
    if said:
        console.print(_text(said), style="dim", soft_wrap=not console.is_terminal)
    for tb in tables(result):
        if not tb["rows"]:
            continue
        t = Table(title=_text(tb["title"]), title_justify="left")
        for h in tb["head"]:
            t.add_column(_text(h), overflow="fold")     # a narrow terminal folds a name, not cuts it
        for r in tb["rows"]:
            t.add_row(*[_text(str(c)) for c in r])
        _print_table(console, t)
        if tb.get("note"):
            console.print(_text(tb["note"]), style="dim", soft_wrap=not console.is_terminal)
    console.print("full summary: summary.json, or drivedyn run --all", style="dim")


def _print_summary(console, result):
    from rich.table import Table

    from .overview import compact
    from ..core.results import flatten, number_text


    from ..core.outputs import shorten

    table = Table(title="summary (SI units)", show_header=True)
    table.add_column("key", overflow="fold")
    table.add_column("value", justify="right", overflow="fold")
    table.add_column("unit", overflow="fold")
    for k, v in flatten(result.summary).items():
        # names are data: no rich markup read from them, and a very long one shortened (the terminal
        # wraps a cell in a time that grows with the square of its length); summary.json has them whole
        if k.startswith(("runup.", "flap.")) and isinstance(v, list):
            continue              # per crank-speed bin: the run-up table, summary.json
        unit = result.units.get(k, "")
        k = _text(shorten(k, 120))
        numeric = isinstance(v, (int, float, list, tuple)) and not isinstance(v, bool)
        if isinstance(v, float):
            v = number_text(v, unit if "speed" in k else "")      # rpm beside speeds, not beside frequencies
        elif isinstance(v, (list, tuple)):
            v = compact(v)
        table.add_row(k, _text(shorten(str(v), 200)), "" if unit == "1" or not numeric else unit)
    _print_table(console, table)


def _print_status(console, result):
    """The status line, then one line per diagnostic (code, text, value against limit)."""

    style = {"success": "green", "warning": "yellow", "failed": "red"}[result.status]
    console.print(f"status: [{style}]{result.status}[/{style}]" + _text(f" ({result.message})" if result.message else ""))
    for d in result.diagnostics:
        numbers = ""
        if d.value is not None and d.limit is not None:
            unit = "" if d.unit in ("", "1") else f" {d.unit}"
            numbers = f" ({d.quantity} = {d.value:.4g}{unit}, limit {d.limit:.4g}{unit})"
        console.print(f"  [yellow]{d.code}[/yellow]: " + _text(d.text + numbers))


@app.command()
def check(model: Path = typer.Argument(..., help="Model file (TOML)."),
          as_json: bool = typer.Option(False, "--json", help="Belt drives: the verdict, steady state, margins, modes "
                                       "and the supplier's tables as JSON."),
          strict: bool = typer.Option(False, "--strict", help=f"Belt drives: exit with status {EXIT_WARNING} when check "
                                      f"warns, {EXIT_CRITERIA} when a design criterion it judges fails (as run)."),
          sets: list[str] = typer.Option(None, "--set", help=SET_HELP)):
    """Validate a model and print what is known without running it, the verdict of what it judges first."""
    from .. import api

    m = _load(model, sets)
    data = None
    try:
        if as_json and m.kind != "belt-drive":
            _fail(f"{model}: check --json is for belt-drive models (this is {m.kind})")
        if m.kind == "belt-drive":
            from ..belt.statics import check_data, json_of, report_and_data

            text, data = (None, check_data(m)) if as_json else report_and_data(m)
            typer.echo(json_of(data) if as_json else text)
        else:
            typer.echo(api.check(m))
    except ModelError as exc:
        _fail(_named(model, exc))
    if strict and data is not None and data.get("warnings"):
        raise typer.Exit(EXIT_WARNING)
    if strict and data is not None and data.get("verdict") == "fail":
        raise typer.Exit(EXIT_CRITERIA)


@app.command()
def schema(kind: str = typer.Argument(..., help="Model kind: belt-drive, gear-train, span-stability, toothed-mesh."),
           out: Optional[Path] = typer.Option(None, "-o", "--out", help="Write to this file instead of printing.")):
    """Print the JSON Schema of a model kind (for TOML editors: Taplo / Even Better TOML): every field
    with its description, SI unit, default and bounds."""
    import json

    from .schema import json_schema

    try:
        text = json.dumps(json_schema(kind), indent=2)
    except ModelError as exc:
        _fail(str(exc))
    if out is None:
        typer.echo(text)
    else:
        from ..core.outputs import write_text

        try:
            write_text(out, text + "\n")      # one line naming the file if it cannot be written
        except OSError as exc:
            _fail(str(exc))
        typer.echo(str(out))


@app.command()
def plot(outdir: Path = typer.Argument(..., help="Folder written by 'drivedyn run'.")):
    """(Re)draw the standard plots of a finished run."""
    from .. import api
    from ..core.results import open_result

    try:
        found = (outdir / "results.nc").is_file()
    except OSError as exc:        # a name too long for the file system, a folder without permission
        _fail(f"{outdir}: cannot read the folder ({exc.strerror or exc})")
    if not found:
        _fail(f"{outdir}: no results.nc here (run 'drivedyn run MODEL -o {outdir}' first)")
    check_outdir(outdir)          # the plots are written into it
    try:
        res = open_result(outdir)
    except (OSError, ValueError) as exc:
        _fail(f"{outdir}: cannot read the run's results.nc and summary.json ({' '.join(str(exc).split())[:200]})")
    try:
        files = api.plot(res, outdir)
    except OSError as exc:
        _fail(str(exc) if isinstance(exc, DrivedynError) else f"{outdir}: cannot write: {exc.strerror or exc}", code=1)
    typer.echo("\n".join(str(f) for f in files))


@app.command()
def examples(name: Optional[str] = typer.Argument(None, help="Example to copy out."),
             to: Path = typer.Option(Path("."), "--to", help="Folder to copy the example into.")):
    """List the shipped example models, or copy one out."""
    from .. import api

    if name is None:
        import textwrap

        width = max(60, shutil.get_terminal_size((100, 20)).columns)
        for stem, path in api.examples().items():
            # the file's first comment paragraph, whole (not cut mid-sentence), wrapped
            para = []
            for ln in path.read_text().splitlines():
                if not ln.startswith("#"):
                    break
                text = ln.lstrip("#").strip()
                if not text:
                    if para:
                        break
                    continue
                para.append(text)
            lines = textwrap.wrap(" ".join(para), width - 29) or [""]
            typer.echo(f"{stem:28s} {lines[0]}")
            for more in lines[1:]:
                typer.echo(" " * 29 + more)
        return
    try:
        src = api.example_path(name)
    except ModelError as exc:
        _fail(str(exc))
    from ..core.outputs import make_folder, write_bytes

    try:
        dest = write_bytes(make_folder(to) / src.name, src.read_bytes())    # replaces a link, never follows it
    except OSError as exc:
        _fail(str(exc))
    typer.echo(str(dest))


@app.command()
def study(study_file: Path = typer.Argument(..., help="Study file (TOML)."),
          out: Optional[Path] = typer.Option(None, "-o", "--out", help="Output folder (default: 'out' of the study file, else its name)."),
          scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Address of a running Dask scheduler (tcp://host:8786)."),
          workers: Optional[int] = typer.Option(None, "--workers", help="Local workers (default: one per core)."),
          retry_failed: bool = typer.Option(False, "--retry-failed", help="Also re-run cases cached as failed."),
          plots: bool = typer.Option(True, help="Draw the study plots."),
          report: bool = typer.Option(True, help="Write report.html (counts, failed cases, plots, study file)."),
          dry_run: bool = typer.Option(False, "--dry-run", help="List the cases without running them."),
          prune: bool = typer.Option(False, "--prune", help="After the run, delete cached cases that are no longer in the study."),
          quiet: bool = typer.Option(False, "-q", "--quiet", help="No progress bar.")):
    """Run a parameter study on Dask (local cluster by default); resumes from its cache."""
    try:
        from . import study_command as study_mod
    except ImportError as exc:
        _fail(f"parameter studies are not available in this build ({exc})")
    try:
        code = study_mod.main(study_file, out=out, scheduler=scheduler, workers=workers, retry_failed=retry_failed,
                              plots=plots, quiet=quiet, dry_run=dry_run, prune=prune, report=report)
    except ModelError as exc:
        _fail(str(exc))
    except OSError as exc:     # a write after the up-front check of the folder (finished cases are cached)
        _fail(f"writing the study's outputs failed: {exc if isinstance(exc, DrivedynError) else exc.strerror or exc}; "
              "finished cases are kept in its cases/ folder", code=1)
    except KeyboardInterrupt:
        _fail("interrupted; finished cases are kept, run the same command again to finish", code=130)
    if code:
        raise typer.Exit(code)


def main(argv=None):
    """Entry point; ``main(["run", "model.toml"])`` runs in-process (tests)."""
    try:    # typer ships its own copy of click
        from typer._click import exceptions as click_errors
    except ImportError:
        from click import exceptions as click_errors

    code = 0
    try:
        # click's own error handling would print a usage box: a mistyped option is one line here
        rv = typer.main.get_command(app).main(args=argv, prog_name="drivedyn", standalone_mode=False)
        code = rv if isinstance(rv, int) else 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except click_errors.NoArgsIsHelpError as exc:    # plain "drivedyn": the help
        exc.show()
        code = 0
    except click_errors.UsageError as exc:
        command = exc.ctx.command_path if exc.ctx is not None else "drivedyn"
        typer.echo(f"drivedyn: error: {' '.join(exc.format_message().split())} (see '{command} --help')", err=True)
        code = 2
    except click_errors.ClickException as exc:
        typer.echo(f"drivedyn: error: {' '.join(exc.format_message().split())}", err=True)
        code = exc.exit_code
    except DrivedynError as exc:  # last resort: never a traceback for a drivedyn error
        typer.echo(f"drivedyn: error: {exc}", err=True)
        code = 2
    if argv is None:
        sys.exit(code)
    return code


if __name__ == "__main__":
    main()
