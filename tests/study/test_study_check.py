"""Studies with mode = "check": each case is what `check` knows (creep theory, margins, modes),
milliseconds per case, for margin maps; the values equal a direct check of the same model."""
import pytest

import drivedyn
from drivedyn.belt.statics import check_data
from drivedyn.study import load_study, run_study

STUDY = """
base = "{belt}"
mode = "check"
[[parameters]]
path = "belt.pretension"
values = ["300 N", "600 N"]
[[parameters]]
name = "load_torque"
path = ["pulleys.driver.torque_time.1.1", "pulleys.driven.torque_speed.0.1", "pulleys.driven.torque_speed.1.1"]
factors = [-1, 1, -1]
unit = "N*m"
values = ["10 N*m", "20 N*m"]
[outputs]
summary = ["steady.slip_margin", "steady.spans.*.tension", "modes.frequencies_hz"]
"""


def test_check_study_equals_direct_checks(client, write_study, tmp_path):
    path = write_study(STUDY)
    res = run_study(path, out=tmp_path / "out", client=client, plots=False)
    ds = res.ds
    assert (ds["status"] == "success").all() and res.counts["ran"] == 4
    base = load_study(path).base
    for T0 in (300.0, 600.0):
        for M in (10.0, 20.0):
            m = drivedyn.replace(base, {"belt.pretension": T0, "pulleys.driver.torque_time.1.1": -M,
                                        "pulleys.driven.torque_speed.0.1": M, "pulleys.driven.torque_speed.1.1": -M})
            ref = check_data(m)["steady"]
            case = ds.sel({"belt.pretension": T0, "load_torque": M})
            want = float("nan") if ref["slip_margin"] is None else ref["slip_margin"]   # None: gross slip
            assert float(case["steady.slip_margin"]) == pytest.approx(want, rel=1e-12, nan_ok=True)
            assert float(case["steady.spans.driver-driven.tension"]) == pytest.approx(
                ref["spans"]["driver-driven"]["tension"], rel=1e-12, nan_ok=True)   # nan: no steady state
    # the margin falls with the load and rises with the pretension
    sm = ds["steady.slip_margin"]
    assert float(sm.sel({"belt.pretension": 600.0, "load_torque": 10.0})) > float(sm.sel({"belt.pretension": 600.0, "load_torque": 20.0}))
    assert float(sm.sel({"belt.pretension": 600.0, "load_torque": 10.0})) > float(sm.sel({"belt.pretension": 300.0, "load_torque": 10.0}))


@pytest.mark.parametrize("text, expect", [
    ('base = "{belt}"\nmode = "check"\n[[parameters]]\npath = "belt.pretension"\nvalues = [300.0]\n'
     '[outputs]\nseries = ["speed"]\n', "no time series"),
    ('base = "GEARS"\nmode = "check"\n[[parameters]]\npath = "drive.speed"\nvalues = [100.0]\n', "for belt-drive models"),
])
def test_check_mode_refusals(write_study, text, expect):
    path = write_study(text.replace("GEARS", str(drivedyn.example_path("gears-split-path"))))
    with pytest.raises(drivedyn.ModelError, match=expect):
        load_study(path)


def test_study_report_in_a_browser(client, write_study, tmp_path):
    # report.html of a study: counts, plots embedded; the page loads in headless Chromium and every
    # image decodes (as tests/api/test_report.py does for runs)
    import re
    import shutil
    import subprocess

    from drivedyn.front.study_report import write_study_report

    path = write_study(STUDY)
    res = run_study(path, out=tmp_path / "out", client=client, plots=True)
    report = write_study_report(res, path, tmp_path / "out")
    html = report.read_text()
    n = int(re.search(r'data-images="(\d+)"', html).group(1))
    assert n == len(res.plots) >= 1 and "4 cases: 4 succeeded" in html
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        pytest.skip("no Chromium on this machine (.ci/run installs it)")
    proc = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom", report.as_uri()],
                          capture_output=True, text=True, timeout=120)
    body = re.search(r"<body[^>]*>", proc.stdout).group(0)
    assert f'data-loaded="{n}"' in body and "broken" not in body, body
