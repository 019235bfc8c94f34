"""Studies: names are data (netCDF variables, file names, plots), the output folder is the one the
user chose and is checked before any case runs, and the size of a study is known before it is
built (a case limit; a dry run lists a large grid in seconds)."""
from __future__ import annotations

import contextlib
import io
import json
import time
import tomllib

import pytest
import tomli_w
import xarray as xr

import drivedyn
from drivedyn.front.cli import main
from drivedyn.study import load_study, run_study

from .conftest import BELT


def cli(*args):
    err = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main([str(a) for a in args])
    return code, err.getvalue(), time.perf_counter() - t0


def last_line(err):
    lines = err.strip().splitlines()
    assert lines and lines[-1].startswith("drivedyn: error:") and "Traceback" not in err, err
    return lines[-1]


ODD = "a/b,c $\\undefinedcmd$"
LONG = "p" * 300


def test_odd_and_long_names_end_in_a_study_dataset_plots_and_report(client, tmp_path):
    base = tomllib.loads(BELT.read_text())
    base["pulleys"][1]["name"] = LONG
    (tmp_path / "base.toml").write_text(tomli_w.dumps(base))
    study = tmp_path / "s.toml"
    study.write_text(f"""
base = "base.toml"
mode = "check"
[[parameters]]
name = {json.dumps(ODD)}
path = "belt.pretension"
values = ["300 N", "600 N"]
[[parameters]]
path = "name"
values = ["$\\\\frac{{$", "plain, with a comma"]
[outputs]
summary = ["steady.slip_margin", "steady.pulleys.*.creep"]
""")
    res = run_study(study, out=tmp_path / "out", client=client)
    ds = xr.load_dataset(res.path, engine="h5netcdf")
    assert (ds["status"] == "success").all()
    label = ODD.replace("/", "_")
    assert label in ds.coords and ds[label].size == 2
    assert json.loads(ds.attrs["parameter_names"]) == [label, "name"]
    assert len(res.plots) == 3 and all(len(p.name) <= 110 for p in res.plots)
    assert any(v.startswith("steady.pulleys.ppp") and "~" in v for v in ds.data_vars)   # shortened, hashed
    from drivedyn.front.study_report import write_study_report

    assert write_study_report(res, study, tmp_path / "out").stat().st_size > 1000


@pytest.mark.parametrize("out", ["../../x", "/tmp/drivedyn-elsewhere", "~/x", "a/../../b"])
def test_a_study_file_does_not_choose_a_folder_outside_the_working_folder(write_study, out):
    path = write_study(f'base = "{{belt}}"\nout = "{out}"\n[[parameters]]\npath = "belt.pretension"\nvalues = [300.0]\n')
    code, err, seconds = cli("study", path, "--dry-run")
    assert code == 2 and "out: must be a folder under the working folder" in last_line(err) and "-o" in err


def test_the_command_line_chooses_any_folder(write_study, tmp_path):
    path = write_study('base = "{belt}"\n[[parameters]]\npath = "belt.pretension"\nvalues = [300.0]\n')
    code, err, _ = cli("study", path, "--dry-run", "-o", tmp_path.resolve() / "elsewhere")
    assert code == 0, err


def test_an_output_folder_that_cannot_be_written_is_refused_before_any_case(write_study, tmp_path):
    path = write_study('base = "{belt}"\n[[parameters]]\npath = "belt.pretension"\nvalues = [300.0]\n')
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "cases").write_text("a file in the way")
    code, err, seconds = cli("study", path, "-o", tmp_path / "out", "-q")
    assert code == 2 and "cannot write the study's output folder" in last_line(err) and seconds < 5


@pytest.mark.parametrize("params, sampler, words", [
    ('[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\nnum = 1e9\n', "", "more than the 100000"),
    ('[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\n', '[sampler]\nmethod = "lhs"\nsamples = 1e9\n',
     "more than the 100000"),
    ('[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\nnum = 1000\n'
     '[[parameters]]\npath = "belt.axial_damping"\nrange = [0.1, 0.2]\nnum = 1000\n', "", "the grid has 1e+06 cases"),
], ids=["num-1e9", "lhs-1e9", "grid-1e6"])
def test_a_study_too_large_is_refused_at_once(write_study, params, sampler, words):
    path = write_study(f'base = "{{belt}}"\n{params}{sampler}')
    code, err, seconds = cli("study", path, "--dry-run")
    assert code == 2 and words in last_line(err) and "DRIVEDYN_MAX_CASES" in err
    assert seconds < 2


def test_a_large_grid_is_listed_in_seconds(write_study, tmp_path):
    path = write_study('base = "{belt}"\n[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\nnum = 500\n'
                       '[[parameters]]\npath = "belt.axial_damping"\nrange = [0.1, 0.2]\nnum = 200\n')
    err = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err):
        code = main(["study", str(path), "--dry-run", "-o", str(tmp_path / "out")])
    assert code == 0 and time.perf_counter() - t0 < 10
    assert "100000 cases" in err.getvalue() and "... and 99950 more" in err.getvalue()
    assert not (tmp_path / "out").exists()      # a dry run writes nothing


def test_the_case_limit_is_raised_through_the_environment(write_study, monkeypatch):
    path = write_study('base = "{belt}"\n[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\nnum = 200000\n')
    with pytest.raises(drivedyn.ModelError, match="DRIVEDYN_MAX_CASES"):
        load_study(path)
    monkeypatch.setenv("DRIVEDYN_MAX_CASES", "300000")
    assert load_study(path).spec.parameters[0].num == 200000


@pytest.mark.parametrize("value, allowed", [("inf", True), ("-inf", False), ("nan", False), ("-1", False), ("abc", False)])
def test_a_garbled_case_limit_reads_as_the_other_limits_do(write_study, monkeypatch, value, allowed):
    """DRIVEDYN_MAX_CASES=inf (or -inf) was int(inf): an OverflowError traceback under every study
    command; now read as DRIVEDYN_MAX_STEPS is: inf lifts it, what is not a positive number is ignored."""
    path = write_study('base = "{belt}"\n[[parameters]]\npath = "belt.pretension"\nrange = ["300 N", "600 N"]\nnum = 200000\n')
    monkeypatch.setenv("DRIVEDYN_MAX_CASES", value)
    if allowed:
        assert load_study(path).spec.parameters[0].num == 200000
    else:
        with pytest.raises(drivedyn.ModelError, match="more than the 100000 cases"):
            load_study(path)


@pytest.mark.parametrize("name", ["study-tensioner-design", "study-pretension"])
def test_an_output_path_that_is_a_file_is_the_only_line(name, tmp_path):
    """An optimisation printed three lines of its header and a progress bar before refusing."""
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    code, err, seconds = cli("study", drivedyn.example_path(name), "-o", blocker)
    assert code == 2 and err.strip() == last_line(err) and "is a file, not a folder" in err and seconds < 5, err


def test_the_dashboard_line_reads_the_schedulers_services():
    """A scheduler started apart without a dashboard was announced with a dashboard link."""
    from drivedyn.front.study_command import _has_dashboard

    class Client:
        def __init__(self, services):
            self.services = services

        def scheduler_info(self):
            return {"services": self.services}

        def run_on_scheduler(self, fn):
            raise OSError("no scheduler here")

    assert not _has_dashboard(Client({}))


@pytest.mark.parametrize("dashboard", [False, True])
def test_a_scheduler_without_a_dashboard_gets_no_link(dashboard):
    """`dask scheduler --no-dashboard` keeps its HTTP server, listed as the service "dashboard"
    (its /status answers 404): the link was printed. Its Bokeh application is what serves one."""
    from distributed import Client, LocalCluster

    from drivedyn.front.study_command import _has_dashboard

    with LocalCluster(n_workers=0, processes=False, dashboard_address=":0",
                      scheduler_kwargs={"dashboard": dashboard}) as cluster, Client(cluster) as client:
        assert "dashboard" in client.scheduler_info()["services"]      # what the old check read
        assert _has_dashboard(client) is dashboard
