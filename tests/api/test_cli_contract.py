"""The command line's side of the status contract: output folder checked before solving, the
status and diagnostics printed, numbers a person reads (no "-0", rpm beside rad/s)."""
import json
import time

import drivedyn
from drivedyn.front.cli import main
from drivedyn.core.results import number_text as _number


def test_output_path_that_is_a_file_is_refused_before_solving(tmp_path, capsys):
    target = tmp_path / "results"
    target.write_text("not a folder")
    t0 = time.perf_counter()
    code = main(["run", str(drivedyn.example_path("belt-5pk")), "-o", str(target), "-q"])
    elapsed = time.perf_counter() - t0
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and "is a file" in err and str(target) in err
    assert elapsed < 5.0                      # the 2 s simulation (about 10 s) never started
    assert target.read_text() == "not a folder"


def test_output_folder_below_a_file_is_refused(tmp_path, capsys):
    blocker = tmp_path / "blocker"
    blocker.write_text("")
    code = main(["run", str(drivedyn.example_path("span-t10")), "-o", str(blocker / "out"), "-q"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and "cannot write the output folder" in err


def test_summary_carries_status_diagnostics_and_units(tmp_path, capsys):
    code = main(["run", str(drivedyn.example_path("span-t10")), "-o", str(tmp_path), "-q", "--no-plots"])
    out = capsys.readouterr().out
    doc = json.loads((tmp_path / "summary.json").read_text())
    assert code == 0
    assert list(doc)[:5] == ["kind", "status", "message", "diagnostics", "units"]
    assert doc["status"] in ("success", "warning")
    assert f"status: {doc['status']}" in out
    for d in doc["diagnostics"]:
        assert set(d) == {"code", "text", "quantity", "value", "limit", "unit"}
        assert d["code"] in out


def test_numbers_as_a_person_reads_them():
    assert _number(-0.0, "1") == "0"
    assert _number(104.71975511965977, "rad/s") == "104.72 (1000 rpm)"


def test_diagnostic_line_shows_quantity_value_and_limit():
    import io

    import xarray as xr
    from rich.console import Console

    from drivedyn.front.cli import _print_status
    from drivedyn.core.results import Result

    r = Result("belt-drive", xr.Dataset())
    r.diagnose("gross-slip", "pulley [a] slips", "pulleys.a.sliding", 0.42, 0.027, "1")
    buf = io.StringIO()
    _print_status(Console(file=buf, width=200), r)
    text = buf.getvalue()
    assert "status: warning" in text
    assert "gross-slip: pulley [a] slips (pulleys.a.sliding = 0.42, limit 0.027)" in text


def test_lowered_limits_refuse_in_one_line_and_leave_the_schema(tmp_path):
    """DRIVEDYN_MAX_STEPS below a gear model's default steps: `schema gear-train` still works, and
    `check` of a model that would exceed it is one line and exit 2 (the gear model's default
    simulation was validated against the limits at import and every gear-train command failed with a
    traceback)."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "DRIVEDYN_MAX_STEPS": "1000"}
    run = lambda *a: subprocess.run([sys.executable, "-m", "drivedyn", *a], capture_output=True, text=True, env=env)
    out = run("schema", "gear-train")
    assert out.returncode == 0 and '"properties"' in out.stdout, out.stderr[-500:]
    out = run("check", str(drivedyn.example_path("gears-split-path")))
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1 and "DRIVEDYN_MAX_STEPS" in out.stderr


def test_step_limit_at_and_just_past_the_limit(monkeypatch):
    """A run at exactly DRIVEDYN_MAX_STEPS is allowed; just past it the refusal prints two different
    numbers (it printed "1e+04 ... more than the 1e+04")."""
    from drivedyn.core.limits import steps_problem

    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "10000")
    assert steps_problem(10000 * (1 + 1e-12), "x", "y") is None
    text = steps_problem(10004, "x", "y")
    assert "10004 integration steps, more than the 10000" in text


def test_a_refusal_while_the_drive_is_assembled_is_the_only_line(tmp_path):
    """`drivedyn run` refused while assembling the drive (here its steps past DRIVEDYN_MAX_STEPS):
    stderr holds the error line alone, not the progress bar's first frame before it."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "DRIVEDYN_MAX_STEPS": "1000"}
    # the layout's kernels compiled first (a cold cache takes seconds, and past BAR_DELAY the bar rightly shows)
    subprocess.run([sys.executable, "-m", "drivedyn", "check", str(drivedyn.example_path("belt-5pk"))],
                   capture_output=True, text=True)
    out = subprocess.run([sys.executable, "-m", "drivedyn", "run", str(drivedyn.example_path("belt-5pk")),
                          "-o", str(tmp_path / "out")], capture_output=True, text=True, env=env)
    assert out.returncode == 2
    lines = [ln for ln in out.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("drivedyn: error:"), out.stderr


def test_set_changes_one_value_from_the_command_line(tmp_path, capsys):
    """--set KEY=VALUE (TOML values; repeatable) on run and check: no edited copy of the file needed;
    a misspelt key or a missing '=' is one line, exit 2."""
    path = str(drivedyn.example_path("fead-runup"))
    code = main(["run", path, "-o", str(tmp_path / "o"), "-q", "--no-plots", "--no-report",
                 "--set", "simulation.model=rotational", "--set", "simulation.runup=periodic",
                 "--set", 'belt.pretension="380 N"'])
    assert code == 0
    doc = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert doc["belt"]["model"] == "rotational" and "runup" in doc
    capsys.readouterr()
    for bad, words in (("belt.pretensoin=3", "did you mean 'pretension'"), ("nonsense", "give KEY=VALUE")):
        assert main(["check", path, "--set", bad]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and words in err, err


def test_the_verdict_says_what_each_criterion_judges(tmp_path, capsys):
    """The verdict names criteria by id; each is followed by what it judges (span_tension read as a
    span's minimum while it is the tension less m v^2), in the terminal and on the report page."""
    assert main(["run", str(drivedyn.example_path("belt-5pk")), "-o", str(tmp_path), "-q", "--no-plots"]) == 0
    out = capsys.readouterr().out
    assert "span_tension: smallest span tension less the centrifugal tension m v^2" in out
    page = (tmp_path / "report.html").read_text()
    assert "what it judges" in page and "less the centrifugal tension" in page
    assert "solve: <span class=\"status" in page


def test_an_output_name_too_long_for_the_file_system_is_one_line(tmp_path, capsys):
    """A folder name over 255 bytes (ENAMETOOLONG) escaped as an OSError traceback from run, study,
    plot and schema: the output path is checked in one place (outputs.check_folder)."""
    import pytest

    long = tmp_path / ("a" * 300)
    commands = [["run", str(drivedyn.example_path("span-t10")), "-o", str(long), "-q"],
                ["study", str(drivedyn.example_path("study-pretension")), "-o", str(long)],
                ["examples", "belt-5pk", "--to", str(long)],
                ["schema", "belt-drive", "-o", str(long)],
                ["schema", "belt-drive", "-o", str(tmp_path / "no-such-folder" / "x.json")],
                ["plot", str(long)]]
    for args in commands:
        t0 = time.perf_counter()
        try:
            code = main(args)
        except OSError as exc:      # the old code's traceback
            pytest.fail(f"{args[0]}: {type(exc).__name__}: {exc}")
        err = capsys.readouterr().err.strip()
        assert code == 2 and len(err.splitlines()) == 1 and err.startswith("drivedyn: error: "), (args[0], err)
        assert ("too long" in err or "No such file" in err) and time.perf_counter() - t0 < 5, (args[0], err)


def test_a_very_long_name_in_a_diagnostic_prints_at_once():
    """The terminal library folds one unbroken word in quadratic time: a 100 000-character pulley name
    took 232 s to print its diagnostic lines. Every long word is shortened for the terminal
    (outputs.shorten_words: its start, '~' and a stable hash; the files keep it whole)."""
    import io
    from types import SimpleNamespace

    from rich.console import Console

    from drivedyn.front.cli import _print_status

    name = "n" * 30_000
    d = SimpleNamespace(code="gross-slip", text=f"pulley {name} slips over its whole wrap", value=1.0, limit=0.0,
                        unit="1", quantity=f"pulleys.{name}.slip")
    result = SimpleNamespace(status="warning", message=f"{name} warned", diagnostics=[d])
    console = Console(file=io.StringIO(), width=80)
    t0 = time.process_time()
    _print_status(console, result)
    assert time.process_time() - t0 < 5.0          # 30 000 characters took about 30 s
    text = console.file.getvalue().replace("\n", "")
    assert "gross-slip" in text and "slips over its whole wrap" in text and name not in text, text[:200]
    from drivedyn.core.outputs import shorten_words

    assert shorten_words(f"a {name} b") == f"a {shorten_words(name)} b" and len(shorten_words(name)) == 300
    assert shorten_words("short words stay") == "short words stay"
