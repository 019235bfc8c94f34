"""A worker killed mid-study: every case still ends exactly once, with its result."""
from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import numpy as np

from drivedyn.study.cases import COMPLETED
from drivedyn.study import run_study

STUDY = """
base = "{belt}"
[overrides]
"simulation.duration" = "0.35 s"
[[parameters]]
path = "belt.pretension"
values = [450.0, 500.0, 550.0, 600.0, 650.0, 700.0, 750.0, 800.0]
[outputs]
summary = ["pulleys.driven.slip", "spans.*.tension_mean"]
"""


def _journal(cache, key):
    lines = (cache / f"{key}.log").read_text().splitlines()
    return [ln.split()[1] for ln in lines]


def test_killed_worker_loses_nothing(client, write_study, tmp_path):
    path = write_study(STUDY)
    out = tmp_path / "out"
    cache = out / "cases"
    killed = []

    def running_case_pid():
        # a case whose journal says "start" and nothing after it is running in that process
        for log in cache.glob("*.log"):
            lines = log.read_text().splitlines()
            if lines and lines[-1].split()[1] == "start":
                return int(lines[-1].split()[2].rsplit(":", 1)[1])
        return None

    def killer():
        # once the study is under way (a first case finished), kill a worker in the middle of a case
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not list(cache.glob("*.json")):
            time.sleep(0.02)
        pid = None
        while time.monotonic() < deadline and pid is None:
            pid = running_case_pid()
            time.sleep(0.005)
        if pid is not None:
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    t = threading.Thread(target=killer, daemon=True)
    t.start()
    res = run_study(path, out=out, client=client, plots=False)
    t.join(5)
    assert killed, "the worker was not killed"
    ds = res.ds
    assert np.isin(ds["status"], COMPLETED).all(), ds["message"].values  # short start-up runs may warn
    assert np.isfinite(ds["pulleys.driven.slip"].values).all()
    keys = ds["case_key"].values.tolist()
    assert len(set(keys)) == 8
    events = {k: _journal(cache, k) for k in keys}
    # no case ran to its end twice, and every case finished: ran to its end, or (killed between
    # writing its record and journaling "end") found finished in the cache by the re-run
    assert all(ev.count("end") <= 1 for ev in events.values()), events
    assert all(ev.count("end") + ev.count("cached") >= 1 for ev in events.values()), events
    # the killed worker's case ran again elsewhere: started anew, or, when the kill came between its
    # record being written and the worker reporting, found finished in the cache
    restarted = sum(ev.count("start") for ev in events.values()) > len(keys)
    assert restarted or any("cached" in ev for ev in events.values()), events
    assert not list(cache.glob("*.json.tmp"))
    client.wait_for_workers(2, timeout=30)  # the nanny restarts the worker for the next tests


def test_worker_without_the_cache_folder_returns_the_record(tmp_path):
    # a remote worker cannot see the client's folder: it returns the record and the series, and the
    # client writes them (same files, same reading)
    import drivedyn
    from drivedyn.study.cases import TOKEN, model_key, read_record, run_case, write_record

    BELT = Path(__file__).resolve().parents[2] / "examples" / "belt-5pk.toml"
    toml = drivedyn.dumps(drivedyn.replace(drivedyn.load(BELT), {"simulation.duration": 0.005}))
    key = model_key(toml)
    rec = run_case(toml, key, str(tmp_path / "elsewhere"), "token", ["speed"])
    assert rec["status"] in COMPLETED and rec["series_data"]["speed"].dims == ("time", "pulley")
    cache = tmp_path / "cases"
    cache.mkdir()
    (cache / TOKEN).write_text("another-token")
    assert run_case(toml, key, str(cache), "token", []).get("series_data", 0) is None  # wrong token: not written
    assert read_record(cache, key) is None
    write_record(cache, key, {k: v for k, v in rec.items() if k != "series_data"}, rec["series_data"])
    back = read_record(cache, key, ["speed"])
    assert back["summary"] == rec["summary"] and (cache / f"{key}.nc").exists()
    assert read_record(cache, key, ["speed", "angle"]) is None  # more series asked for: run again


def test_case_timeout_stops_a_case_and_keeps_what_it_computed(tmp_path):
    # a belt case stopped by its wall-time limit: "failed", the reason in the message, and the
    # samples simulated so far in the record (summary) and the series
    import drivedyn
    from drivedyn.study.cases import model_key, run_case

    BELT = Path(__file__).resolve().parents[2] / "examples" / "belt-5pk.toml"
    toml = drivedyn.dumps(drivedyn.replace(drivedyn.load(BELT), {"simulation.duration": 0.2}))
    rec = run_case(toml, model_key(toml), str(tmp_path / "elsewhere"), "token", ["speed"], timeout=1e-9)
    assert rec["status"] == "failed" and "case_timeout of 1e-09 s" in rec["message"], rec["message"]
    n = rec["series_data"].sizes["time"]
    assert 1 <= n < 200  # stopped at the first progress report (1 % of the 200 samples)
    assert rec["summary"]["solver.steps"] > 0

    # an analysis that keeps nothing when stopped (gear train: reports only between phases)
    GEARS = Path(__file__).resolve().parents[2] / "examples" / "gears-split-path.toml"
    toml = drivedyn.dumps(drivedyn.load(GEARS))
    rec = run_case(toml, model_key(toml), str(tmp_path / "elsewhere"), "token", [], timeout=1e-9)
    assert rec["status"] == "failed" and rec["message"].startswith("stopped: case_timeout"), rec["message"]


def test_case_timeout_in_the_study_file(write_study):
    from drivedyn.study.spec import load_study

    study = load_study(write_study("""
        base = "{belt}"
        case_timeout = "2 min"
        [[parameters]]
        path = "belt.pretension"
        values = ["0.4 kN"]
    """))
    assert study.spec.case_timeout == 120.0


def test_ctrl_c_ends_the_study_in_its_one_line(write_study, tmp_path):
    """Ctrl-C reaches every process of the terminal's group: the workers died with it and the
    scheduler and client printed Dask's CommClosedError lines and tracebacks before the one line.
    Now the workers ignore it (the client stops them) and the closing is quiet."""
    import subprocess
    import sys

    path = write_study(STUDY)
    err = tmp_path / "stderr"
    with open(err, "w") as fh:
        proc = subprocess.Popen([sys.executable, "-m", "drivedyn", "study", str(path), "-o", str(tmp_path / "out"),
                                 "--workers", "1"], stdout=subprocess.DEVNULL, stderr=fh, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while "dask scheduler" not in err.read_text() and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.2)
        time.sleep(4)                    # the worker warming up or running a case
        os.killpg(proc.pid, signal.SIGINT)     # what the terminal sends on Ctrl-C
        code = proc.wait(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    text = err.read_text()
    assert code == 130, text
    assert "Traceback" not in text and "CommClosedError" not in text and " - ERROR - " not in text, text
    assert text.strip().splitlines()[-1].startswith("drivedyn: error: interrupted; finished cases are kept")
