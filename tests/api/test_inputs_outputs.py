"""Every input and output path ends in a result or one line (exit 2 for a user's mistake, 1 for a
write that failed after the up-front check), before anything long or large starts; names are data
in every plot and file; outputs stay in the folder the user chose; silently wrong belt inputs are
refused or flagged. Each test here failed before these checks existed."""
from __future__ import annotations

import contextlib
import io
import json
import math
import os
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

import drivedyn
from drivedyn.front.cli import main
from drivedyn.core.errors import ModelError


def cli(*args):
    err, out = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        code = main([str(a) for a in args])
    return code, err.getvalue(), out.getvalue(), time.perf_counter() - t0


def one_line(err: str) -> str:
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    assert len(lines) >= 1 and lines[-1].startswith("drivedyn: error:"), err
    assert "Traceback" not in err
    return lines[-1]


def example(name: str) -> dict:
    return tomllib.loads(drivedyn.example_path(name).read_text())


def short_belt(**changes) -> dict:
    """The 5PK drive, 10 ms (well under a second once the kernels are compiled)."""
    d = example("belt-5pk")
    d["simulation"]["duration"] = "0.01 s"
    d["output"]["frames"] = 2
    for path, value in changes.items():
        node = d
        parts = path.split(".")
        for p in parts[:-1]:
            node = node[int(p)] if isinstance(node, list) else node[p]
        node[int(parts[-1]) if isinstance(node, list) else parts[-1]] = value
    return d


def write(tmp_path, data: dict, name="m.toml") -> Path:
    path = tmp_path / name
    path.write_text(tomli_w.dumps(data))
    return path


# ------------------------------------------------------------------ names are data in plots

def test_savefig_draws_math_text_literally(tmp_path):
    from matplotlib.figure import Figure

    from drivedyn.core.plotting import savefig

    fig = Figure()
    ax = fig.subplots()
    ax.plot([0, 1], [0, 1], label=r"$\undefinedcmd$")
    ax.legend()
    ax.set_title(r"pulley $\undefinedcmd$")
    ax.set_xticks([0, 1], [r"$\frac{$", "$x^$"])
    path = savefig(fig, tmp_path / "f.png")
    assert path.stat().st_size > 1000


def test_a_dollar_pulley_name_runs_with_plots_and_report(tmp_path):
    path = write(tmp_path, short_belt(**{"pulleys.0.name": r"$\undefinedcmd$"}))
    code, err, _, _ = cli("run", path, "-o", tmp_path / "out", "-q")
    assert code == 0, err
    assert "Traceback" not in err
    assert (tmp_path / "out" / "speeds.png").exists() and (tmp_path / "out" / "report.html").exists()


def test_rich_markup_in_a_name_is_printed_as_written(tmp_path):
    path = write(tmp_path, short_belt(**{"pulleys.0.name": "[bold]x[red]"}))
    code, err, out, _ = cli("run", path, "-o", tmp_path / "out", "-q", "--no-plots", "--no-report")
    assert code == 0, err
    assert "[bold]x[red]" in out


def test_a_100000_character_name_is_shortened_on_the_terminal_and_kept_in_the_summary(tmp_path):
    name = "p" * 100_000
    path = write(tmp_path, short_belt(**{"pulleys.0.name": name}))    # the driver: a summary value too
    code, err, out, seconds = cli("run", path, "-o", tmp_path / "out", "-q", "--no-plots", "--no-report")
    assert code == 0, err
    assert seconds < 60             # 232 s before (the terminal wrapped the cell)
    assert max(len(ln) for ln in (err + out).splitlines()) < 400
    assert name in json.loads((tmp_path / "out" / "summary.json").read_text())["pulleys"]


def test_run_prints_its_findings_on_stdout(tmp_path):
    """`drivedyn run m.toml -o out > log.txt` keeps the verdict, the tables and the status (they went
    to stderr and left the file empty); progress and errors stay on stderr."""
    code, err, out, _ = cli("run", write(tmp_path, short_belt()), "-o", tmp_path / "out", "-q", "--no-plots")
    assert code == 0, err
    assert "verdict:" in out and "status:" in out and "report:" in out
    assert "verdict:" not in err


def test_piped_tables_keep_their_names_whole(tmp_path):
    """Written to a file or a pipe, rich sizes a console at 80 columns and cut every table's names to
    8 characters ("tensio…", "(compr…") and folded its numbers ("762 .." over "5018"); the tables
    are printed at the width their columns need now (a long cell folds at cli.PIPE_WIDTH)."""
    from drivedyn.front.cli import PIPE_WIDTH

    names = ("crankshaft_main_pulley", "alternator_with_clutch")
    d = short_belt(**{"pulleys.0.name": names[0], "pulleys.1.name": names[1]})
    code, err, out, _ = cli("run", write(tmp_path, d), "-o", tmp_path / "out", "-q", "--no-plots")
    assert code == 0, err
    rows = [ln for ln in out.splitlines() if ln.startswith("\u2502")]      # table rows
    assert rows and not any("\u2026" in ln for ln in rows)
    for nm in names:
        assert any(f"\u2502 {nm} " in ln for ln in rows), nm          # a whole name in its own cell
    assert f"{names[0]}-{names[1]}" in out                               # a span's name, whole
    assert max(len(ln) for ln in out.splitlines() if ln[:1] in "\u250f\u2502\u2514") <= PIPE_WIDTH


def test_a_narrow_terminal_folds_names_not_cuts_them(tmp_path):
    """In a terminal of 60 columns the tables fold a long name over lines (rich's default cut it to
    "alternat…")."""
    from rich.console import Console

    from drivedyn.front.cli import _print_overview

    names = ("crankshaft_main_pulley", "alternator_with_clutch")
    d = short_belt(**{"pulleys.0.name": names[0], "pulleys.1.name": names[1]})
    result = drivedyn.run(drivedyn.load(write(tmp_path, d)))
    buf = io.StringIO()
    _print_overview(Console(file=buf, width=60, force_terminal=True, color_system=None), result)
    text = buf.getvalue()
    assert "\u2026" not in text
    joined = "".join(ln.split("\u2502")[1].strip() if ln.count("\u2502") > 2 else "" for ln in text.splitlines())
    assert all(nm in joined for nm in names)         # each name whole once its folded pieces are joined


def test_file_and_netcdf_names():
    from drivedyn.core.outputs import file_stem, nc_name

    long = "k" * 300
    assert len(file_stem(long)) <= 100 and file_stem(long) == file_stem(long) != file_stem(long + "x")
    assert file_stem("a/b,c $x$") == "a_b_c__x_"
    assert "/" not in nc_name("a/b") and len(nc_name(long)) <= 200


# ------------------------------------------------------------------ write failures, links

def test_a_link_in_the_output_folder_is_replaced_not_followed(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "out"
    out.mkdir()
    for name in ("summary.json", "results.nc", "report.html"):
        (out / name).symlink_to(victim)
    code, err, _, _ = cli("run", write(tmp_path, short_belt()), "-o", out, "-q", "--no-plots")
    assert code == 0, err
    assert victim.read_text() == "keep me"
    assert not (out / "summary.json").is_symlink()
    json.loads((out / "summary.json").read_text())


@pytest.mark.parametrize("in_the_way", ["results.nc", "summary.json", "report.html"])
def test_a_folder_in_the_way_of_an_output_ends_as_a_failed_run_in_one_line(tmp_path, in_the_way):
    out = tmp_path / "out"
    (out / in_the_way).mkdir(parents=True)
    code, err, _, _ = cli("run", write(tmp_path, short_belt()), "-o", out, "-q", "--no-plots")
    assert code == 1
    line = one_line(err)
    assert in_the_way in line and "written:" in line
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]    # no temporary file left


def test_a_failed_write_names_what_was_kept(tmp_path):
    out = tmp_path / "out"
    (out / "report.html").mkdir(parents=True)
    code, err, _, _ = cli("run", write(tmp_path, short_belt()), "-o", out, "-q", "--no-plots")
    line = one_line(err)
    assert code == 1 and "results.nc" in line.split("written:")[1] and "summary.json" in line


def test_examples_copy_replaces_a_link(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    (tmp_path / "belt-5pk.toml").symlink_to(victim)
    code, err, _, _ = cli("examples", "belt-5pk", "--to", tmp_path)
    assert code == 0, err
    assert victim.read_text() == "keep me"


# ------------------------------------------------------------------ files read with a cap

def test_a_device_and_a_pipe_are_refused_at_once(tmp_path):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    for path in ("/dev/zero", fifo):
        code, err, _, seconds = cli("check", path)
        assert code == 2 and "not a regular file" in one_line(err) and seconds < 2


def test_a_study_base_on_a_device_is_refused(tmp_path):
    study = tmp_path / "s.toml"
    study.write_text('base = "/dev/zero"\n[[parameters]]\npath = "belt.pretension"\nvalues = [1]\n')
    code, err, _, seconds = cli("study", study, "--dry-run")
    assert code == 2 and "not a regular file" in one_line(err) and seconds < 2


# ------------------------------------------------------------------ cost known before the solve

@pytest.mark.parametrize("model, changes, words", [
    ("belt-5pk", {"simulation.duration": "1e5 s"}, "GB"),
    ("belt-5pk", {"output.interval": "1e-9 s"}, "GB"),
    ("belt-5pk", {"output.interval": "1e-30 s"}, "GB"),
    ("belt-5pk", {"simulation.step": "1e-12 s"}, "integration steps"),
    ("belt-5pk", {"simulation.method": "rkf45"}, "rkf45 is explicit"),
    ("fead-runup", {"output.runup_bin": "1e-6 rpm"}, "bins"),
    ("gears-split-path", {"simulation.step": "1e-13 s"}, "integration steps"),
    ("gears-split-path", {"simulation.output_interval": "1e-12 s", "simulation.step": "1e-6 s",
                          "simulation.duration": "900 s"}, "GB"),
])
def test_a_run_too_large_for_the_machine_is_refused_up_front(tmp_path, model, changes, words):
    data = example(model)
    for k, v in changes.items():
        a, b = k.split(".")
        data.setdefault(a, {})[b] = v
    t0 = time.perf_counter()
    code, err, _, _ = cli("check", write(tmp_path, data))
    line = one_line(err)
    assert code == 2 and words in line and ("DRIVEDYN_MAX" in line) == (words != "bins")
    assert time.perf_counter() - t0 < 2


def test_the_limits_are_raised_through_the_environment(monkeypatch):
    m = drivedyn.load(drivedyn.example_path("belt-5pk"))
    with pytest.raises(ModelError, match="integration steps"):
        drivedyn.replace(m, {"simulation.step": 1e-9, "simulation.duration": 2.0})
    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "1e10")
    drivedyn.replace(m, {"simulation.step": 1e-9, "simulation.duration": 2.0})


def test_the_shipped_examples_stay_within_the_limits():
    for name, path in drivedyn.examples().items():
        if not name.startswith("study"):
            drivedyn.load(path)


# ------------------------------------------------------------------ silently wrong belt inputs

def test_a_one_way_clutch_on_the_torque_driven_pulley_is_refused():
    d = short_belt()
    d["pulleys"][0]["clutch"] = {"type": "one-way", "inertia": "1e-3 kg*m^2"}
    with pytest.raises(ModelError, match=r"pulleys\[0\]\.clutch: .*drives the belt"):
        drivedyn.loads(tomli_w.dumps(d))


def test_speed_orders_on_a_standing_crank_are_refused():
    d = example("fead-runup")
    crank = next(p for p in d["pulleys"] if p.get("speed_orders"))
    crank["speed_time"] = [["0 s", "0 rpm"], ["1 s", "0 rpm"]]
    with pytest.raises(ModelError, match="turning crank"):
        drivedyn.loads(tomli_w.dumps(d))


@pytest.mark.parametrize("extra", [{"rate": "10 N*m/rad"}, {"preload": "5 N*m"}])
def test_a_spring_table_beside_rate_or_preload_is_refused(extra):
    d = example("fead-runup")
    arm = next(p["arm"] for p in d["pulleys"] if "arm" in p)
    arm.pop("rate", None), arm.pop("preload", None)
    arm["spring_table"] = [["-0.5 rad", "30 N*m"], ["0.5 rad", "10 N*m"]]
    drivedyn.loads(tomli_w.dumps(d))             # the table alone is fine
    arm.update(extra)
    with pytest.raises(ModelError, match="spring_table or preload and rate, not both"):
        drivedyn.loads(tomli_w.dumps(d))


@pytest.mark.parametrize("order", [-1e29, 0, 1001])
def test_harmonic_orders_are_bounded(order):
    d = short_belt()
    d["pulleys"][1]["harmonics"] = [{"order": order, "amplitude": "1 N*m"}]
    with pytest.raises(ModelError, match=r"harmonics\[0\]\.order: must lie in \(0, 1000\]"):
        drivedyn.loads(tomli_w.dumps(d))


def test_a_torque_speed_table_read_the_wrong_way_round_is_flagged():
    """The driven pulley turns clockwise (negative speeds); a load table written with positive
    speeds is extrapolated through zero and drives the belt: two diagnostics, status warning."""
    d = short_belt(**{"simulation.duration": "0.03 s"})
    d["pulleys"][0].pop("torque_time")
    d["pulleys"][0]["torque"] = "-15 N*m"
    d["pulleys"][1]["torque_speed"] = [["0 rad/s", "0 N*m"], ["100 rad/s", "5 N*m"]]
    r = drivedyn.run(drivedyn.loads(tomli_w.dumps(d)))
    codes = {x.code for x in r.diagnostics}
    assert {"table-extrapolated", "load-delivers-power"} <= codes and r.status == "warning"
    delivered = next(x for x in r.diagnostics if x.code == "load-delivers-power")
    assert delivered.value == pytest.approx(r.summary["pulleys"]["driven"]["power_mean"])
    assert delivered.value > delivered.limit
    # the same table written for the pulley's running sense: a load, no diagnostic of these
    d["pulleys"][1]["torque_speed"] = [["-100 rad/s", "5 N*m"], ["0 rad/s", "0 N*m"]]
    r = drivedyn.run(drivedyn.loads(tomli_w.dumps(d)))
    assert not {"table-extrapolated", "load-delivers-power"} & {x.code for x in r.diagnostics}
    assert r.summary["pulleys"]["driven"]["power_mean"] < 0


@pytest.mark.parametrize("w2, refused", [(-100.0, True), (150.0, True), (100.0, False), (101.0, False)])
def test_two_prescribed_speeds_must_agree_on_the_belt_speed(tmp_path, w2, refused):
    d = example("belt-5pk")
    d["pulleys"][0].pop("torque_time")
    d["pulleys"][1].pop("torque_speed", None)
    d["pulleys"][0]["speed_time"] = [[0, 100.0], [1, 100.0]]       # equal radii: the same speed, same sense
    d["pulleys"][1]["speed_time"] = [[0, w2], [1, w2]]
    code, err, out, _ = cli("check", write(tmp_path, d))
    if refused:
        assert code == 2 and "the belt would slide on one of them" in one_line(err)
    else:
        assert code == 0 and "running steady" in out


def test_check_says_when_a_table_is_read_outside_its_range():
    d = example("belt-5pk")
    d["pulleys"][0]["torque_time"] = [[0, -15.0], [1, -15.0]]
    d["pulleys"][1]["torque_speed"] = [["-20 rad/s", "10 N*m"], ["-10 rad/s", "5 N*m"]]    # balances at -30 rad/s
    text = drivedyn.check(drivedyn.loads(tomli_w.dumps(d)))
    assert "warning: pulley driven runs at -30 rad/s, outside its torque_speed table [-20, -10] rad/s" in text
    assert "outside its torque_speed" not in drivedyn.check(drivedyn.example_path("belt-5pk"))


def test_a_disk_that_fills_up_ends_the_run_in_one_line(tmp_path, monkeypatch):
    import errno

    import drivedyn.core.outputs as outputs

    def full(src, dst):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(outputs.os, "replace", full)
    out = tmp_path / "out"
    code, err, _, _ = cli("run", write(tmp_path, short_belt()), "-o", out, "-q", "--no-plots")
    assert code == 1 and "No space left on device" in one_line(err) and "written: nothing" in one_line(err)
    assert not list(out.iterdir())                  # no temporary file left behind


@pytest.mark.parametrize("name, old", [("gears-split-path", '"pinion"'), ("mesh-htd8m", '"L / L z20 (fig. 7)"')])
def test_math_text_in_gear_names_and_compare_labels_is_drawn_literally(tmp_path, name, old):
    d = example(name)
    if d["kind"] == "gear-train":
        d["sweep"] = {"enabled": False}
        d["simulation"].update(duration="2 ms", steady_window=["1 ms", "2 ms"])
    else:
        d["mesh"]["angles"] = 15
        d.setdefault("maps", {})["angles"] = 5
    text = tomli_w.dumps(d)
    assert old in text
    path = tmp_path / "m.toml"
    path.write_text(text.replace(old, '"$\\\\undefinedcmd$"'))      # every reference to the name
    code, err, _, _ = cli("run", path, "-o", tmp_path / "out", "-q")
    assert code == 0, err
    assert (tmp_path / "out" / "report.html").exists()


# ------------------------------------------------------------------ toothed [load]

@pytest.mark.parametrize("changes, code, words", [
    ({"wrap": "5 deg"}, 2, "no whole tooth"),
    ({"clearance": "1 m"}, 2, "half the groove spacing"),
    ({"tooth_modulus": "1e20 Pa"}, 1, "did not converge"),
])
def test_toothed_load_extremes_end_in_one_line(tmp_path, changes, code, words):
    d = example("mesh-load-l")
    d["load"].update(changes)
    got, err, _, _ = cli("run", write(tmp_path, d), "-o", tmp_path / "out", "-q", "--no-plots", "--no-report")
    assert got == code and words in one_line(err)


# ------------------------------------------------------------------ messages and JSON

def test_nm_is_named_as_nanometre():
    d = short_belt()
    d["pulleys"][0]["torque_time"] = [["0 s", "0 Nm"], ["0.3 s", "-15 Nm"]]
    with pytest.raises(ModelError, match=r"'Nm' reads as nanometre, write newton-metres as 'N\*m'"):
        drivedyn.loads(tomli_w.dumps(d))


def _strict(text):
    def refuse(c):
        raise ValueError(f"not strict JSON: {c}")
    return json.loads(text, parse_constant=refuse)


def test_check_json_is_strict_where_no_steady_state_exists(tmp_path):
    d = example("belt-5pk")
    d["pulleys"][0].pop("torque_time")
    d["pulleys"][0]["speed_time"] = [[0, 5000.0], [1, 5000.0]]    # m v^2 = 1750 N > 550 N: a span goes slack
    code, err, out, _ = cli("check", write(tmp_path, d), "--json")
    assert code == 0, err
    assert "NaN" not in out
    doc = _strict(out)
    assert doc["steady"]["spans"]["driver-driven"]["tension"] is None


def test_summary_json_is_strict(tmp_path):
    import xarray as xr

    from drivedyn.core.results import Result

    r = Result("belt-drive", xr.Dataset(), {"a": float("nan"), "b": [1.0, float("inf")], "c": np.float64("nan")})
    r.diagnose("gross-slip", "x", "q", float("nan"), 1.0)
    r.save(tmp_path)
    doc = _strict((tmp_path / "summary.json").read_text())
    assert doc["a"] is None and doc["b"] == [1.0, None] and doc["diagnostics"][0]["value"] is None


@pytest.mark.parametrize("args, words", [
    (["run", "--bogus", "m.toml"], "No such option: --bogus"),
    (["check"], "Missing argument"),
    (["nosuch"], "No such command"),
    (["study", "s.toml", "--workers", "many"], "Invalid value for '--workers'"),
])
def test_a_command_line_mistake_is_one_line(args, words):
    code, err, out, _ = cli(*args)
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and words in one_line(err)


def test_plot_of_a_damaged_folder_is_one_line(tmp_path):
    (tmp_path / "results.nc").write_text("not netcdf")
    (tmp_path / "summary.json").write_text("{}")
    code, err, _, _ = cli("plot", tmp_path)
    assert code == 2 and "cannot read" in one_line(err)


def test_nothing_is_left_when_no_steady_state_is_nan_in_the_json_of_a_run(tmp_path):
    path = write(tmp_path, short_belt())
    code, err, _, _ = cli("run", path, "-o", tmp_path / "out", "-q", "--no-plots", "--no-report")
    assert code == 0, err
    doc = _strict((tmp_path / "out" / "summary.json").read_text())
    assert doc["status"] in ("success", "warning")
    assert not math.isnan(doc["belt"]["pretension"])


def test_the_long_fuzz_runs_findings_end_in_one_line(tmp_path):
    """Three cases the long fuzz run found: a belt whose stable step is a nanosecond (contact
    stiffness 2^62: 6e8 steps, hours, within the step limit) is refused before the solve; a
    tensioner pulley with a drag of 1e29 N m (no steady state) is checked without a traceback, its
    modes at rest; a zero flank roughness (ISO 6336-2's Z_R divides by it) is refused."""
    d = example("belt-verification")
    d["contact"]["stiffness_linear"] = 2.0 ** 62
    code, err, out, _ = cli("run", str(write(tmp_path, d)), "-o", str(tmp_path / "o"), "--no-plots")
    assert code == 2 and "stable step" in one_line(err)
    d = example("fead-runup")
    d["pulleys"][5]["drag"] = 1e29
    code, err, out, _ = cli("check", str(write(tmp_path, d, "t.toml")))
    assert code == 0 and "Traceback" not in err
    d = example("gears-helical-tr6336")
    d["iso"]["flank_roughness"] = 0.0
    code, err, out, _ = cli("check", str(write(tmp_path, d, "g.toml")))
    assert code == 2 and "flank_roughness" in one_line(err)


def test_summary_units_take_the_first_pattern_that_matches():
    """The units of a summary's dotted keys: the first of the fnmatch patterns in their order that
    matches a key (one regex of them all), no unit where none does."""
    from drivedyn.core.results import unit_map

    patterns = {"spans.*.tension_*": "N", "spans.*": "1", "power.efficiency": "1", "power.*": "W"}
    summary = {"spans": {"a-b": {"tension_min": 1.0, "speed_mean": 2.0}}, "power": {"efficiency": 0.9, "loss": 3.0},
               "solver": {"steps": 10}}
    assert unit_map(summary, patterns) == {"spans.a-b.tension_min": "N", "spans.a-b.speed_mean": "1",
                                           "power.efficiency": "1", "power.loss": "W"}
