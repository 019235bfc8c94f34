"""Studies on a real LocalCluster: results equal single runs, failures are recorded, resume is free."""
from __future__ import annotations

import numpy as np
import xarray as xr

import drivedyn
from drivedyn.study.cases import COMPLETED
from drivedyn.study import load_study, run_study

GRID = """
name = "grid"
base = "{belt}"
[overrides]
"simulation.duration" = "0.02 s"
[[parameters]]
path = "belt.pretension"
values = ["450 N", "600 N"]
[[parameters]]
name = "load_torque"
path = ["pulleys.driver.torque_time.1.1", "pulleys.driven.torque_speed.0.1", "pulleys.driven.torque_speed.1.1"]
factors = [-1, 1, -1]
range = ["5 N*m", "15 N*m"]
num = 3
[outputs]
summary = ["pulleys.*.speed_mean", "pulleys.driven.slip", "spans.*.tension_mean", "solver.status"]
series = ["speed"]
"""


def _single(base, pretension, torque):
    m = drivedyn.replace(base, {"belt.pretension": pretension, "pulleys.driver.torque_time.1.1": -torque,
                                "pulleys.driven.torque_speed.0.1": torque, "pulleys.driven.torque_speed.1.1": -torque})
    return drivedyn.run(m)


def test_grid_study_matches_single_runs(client, write_study, tmp_path):
    path = write_study(GRID)
    res = run_study(path, out=tmp_path / "out", client=client, plots=True)
    ds = res.ds
    assert dict(ds.sizes)["belt.pretension"] == 2 and dict(ds.sizes)["load_torque"] == 3
    assert ds["load_torque"].values.tolist() == [5.0, 10.0, 15.0]
    assert ds["belt.pretension"].attrs["units"] == "N"
    # summary values keep the cases' units (the study plots label axes and colour bars with them)
    assert ds["spans.driver-driven.tension_mean"].attrs["units"] == "N"
    assert ds["pulleys.driven.speed_mean"].attrs["units"] == "rad/s"
    assert np.isin(ds["status"], COMPLETED).all()
    assert res.counts["ran"] == 6 and res.counts["cached"] == 0
    assert "[[parameters]]" in ds.attrs["study_toml"] and 'kind = "belt-drive"' in ds.attrs["base_model_toml"]
    base = load_study(path).base
    for p in ds["belt.pretension"].values:
        for t in ds["load_torque"].values:
            ref = _single(base, float(p), float(t))
            case = ds.sel({"belt.pretension": p, "load_torque": t})
            for key in ("pulleys.driver.speed_mean", "pulleys.driven.speed_mean", "pulleys.driven.slip",
                        "spans.driver-driven.tension_mean"):
                np.testing.assert_allclose(float(case[key]), ref.flat_summary()[key], rtol=1e-12, err_msg=key)
            assert str(case["solver.status"].values) == "success"
            np.testing.assert_allclose(case["speed"].values, ref.ds["speed"].values, rtol=1e-12)
    # the file on disk is the same Dataset
    back = xr.load_dataset(res.path, engine="h5netcdf")
    np.testing.assert_array_equal(back["pulleys.driven.slip"].values, ds["pulleys.driven.slip"].values)
    assert back["status"].values.tolist() == ds["status"].values.tolist()
    assert len(res.plots) >= 4 and all(p.stat().st_size > 1000 for p in res.plots)

    # resume: nothing changed, nothing runs, same numbers
    again = run_study(path, out=tmp_path / "out", client=client, plots=False)
    assert again.counts["ran"] == 0 and again.counts["cached"] == 6
    xr.testing.assert_identical(again.ds.drop_attrs(), ds.drop_attrs())

    # change one value of one parameter: only the 3 cases of the new value run
    path.write_text(path.read_text().replace('"600 N"', '"650 N"'))
    third = run_study(path, out=tmp_path / "out", client=client, plots=False)
    assert third.counts["ran"] == 3 and third.counts["cached"] == 3
    assert np.isin(third.ds["status"], COMPLETED).all()


def test_failing_cases_are_recorded_and_the_rest_complete(client, write_study, tmp_path):
    # -1 N fails validation (on the client), 2e5 N is refused by the analysis (on the worker),
    # a 20 us step diverges (SolverError with partial results) in the semi-implicit scheme at the
    # seed's 150 segments
    path = write_study("""
        base = "{belt}"
        [overrides]
        "simulation.duration" = "0.01 s"
        "simulation.method" = "semi-implicit"
        "belt.segments" = 150
        "output.segments" = [0]
        [[parameters]]
        path = "belt.pretension"
        values = [550.0, -1.0, 2e5]
        [[parameters]]
        path = "simulation.step"
        values = ["2 us", "20 us"]
        [outputs]
        summary = ["pulleys.driven.slip", "solver.simulated_time"]
    """)
    res = run_study(path, out=tmp_path / "out", client=client, plots=True)
    st = res.ds["status"]
    msg = res.ds["message"]
    ok = st.sel({"belt.pretension": 550.0, "simulation.step": 2e-6})
    assert str(ok.values) in COMPLETED
    assert np.isfinite(float(res.ds["pulleys.driven.slip"].sel({"belt.pretension": 550.0, "simulation.step": 2e-6})))
    bad_value = msg.sel({"belt.pretension": -1.0})
    assert (st.sel({"belt.pretension": -1.0}) == "invalid").all()
    assert all("belt.pretension" in str(m) and "must be > 0 N" in str(m) for m in bad_value.values)
    refused = st.sel({"belt.pretension": 2e5})
    assert (refused == "invalid").all()
    assert "pretension too high" in str(msg.sel({"belt.pretension": 2e5, "simulation.step": 2e-6}).values)
    diverged = res.ds.sel({"belt.pretension": 550.0, "simulation.step": 2e-5})
    assert str(diverged["status"].values) == "failed" and "diverged" in str(diverged["message"].values)
    assert float(diverged["solver.simulated_time"]) < 0.01  # the partial summary is kept
    assert res.counts["success"] + res.counts["warning"] == 1 and res.counts["invalid"] == 4 and res.counts["failed"] == 1
    # failures are cached too: a resume runs nothing unless asked to retry them
    assert run_study(path, out=tmp_path / "out", client=client, plots=False).counts["ran"] == 0
    assert run_study(path, out=tmp_path / "out", client=client, plots=False, retry_failed=True).counts["ran"] == 3


def test_sampled_design_gives_a_case_dimension(client, write_study, tmp_path):
    path = write_study("""
        base = "{belt}"
        [overrides]
        "simulation.duration" = "0.01 s"
        [[parameters]]
        path = "belt.pretension"
        range = ["400 N", "700 N"]
        [[parameters]]
        path = "pulleys.driven.inertia"
        range = [0.01, 0.04]
        scale = "log"
        [sampler]
        method = "lhs"
        samples = 5
        seed = 7
        [outputs]
        summary = ["pulleys.driven.slip"]
    """)
    res = run_study(path, out=tmp_path / "out", client=client)
    ds = res.ds
    assert ds["pulleys.driven.slip"].dims == ("case",) and ds.sizes["case"] == 5
    assert ds["belt.pretension"].dims == ("case",)
    pre = np.sort(ds["belt.pretension"].values)
    # Latin hypercube: one sample in each fifth of the range
    assert np.array_equal(np.floor((pre - 400.0) / 60.0), np.arange(5))
    assert ((ds["pulleys.driven.inertia"] >= 0.01) & (ds["pulleys.driven.inertia"] <= 0.04)).all()
    assert np.isin(ds["status"], COMPLETED).all() and len(res.plots) == 1
    # the same seed gives the same cases: all cached
    assert run_study(path, out=tmp_path / "out", client=client, plots=False).counts["ran"] == 0
