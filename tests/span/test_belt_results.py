"""The span analysis reading a belt-drive run's results.nc: span, tension and speed from the run."""
import pytest
import xarray as xr

import drivedyn
from drivedyn.mechanics.layout import compute_layout
from drivedyn.core.model import from_dict


@pytest.fixture(scope="module")
def belt_run(tmp_path_factory):
    """A short 5PK run (80 segments, 0.4 s, window 0.3-0.4 s) saved as results.nc."""
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                         {"belt.segments": 80, "output.segments": [0], "simulation.duration": 0.4, "output.steady_window": [0.3, 0.4],
                          "output.frames": 2})
    out = tmp_path_factory.mktemp("belt")
    r = drivedyn.run(m)
    r.save(out)
    return out / "results.nc", m, r


def span_model(path, **more):
    data = {"kind": "span-stability",
            "span": {"belt_results": str(path), "span_name": "driven-driver"},
            # the segment chain's polygon frequency v / l excites the span: pitch = segment length
            "excitation": {"teeth": 1, "pitch": 1.2 / 80, "harmonics": 3},
            "tooth_force": {"series": str(path)},
            "chart": {"points": [12, 12], "floquet": False, "zoom": {"points": [6, 6]}}}
    for k, v in more.items():
        data[k] = v
    return from_dict(data)


def test_span_tension_and_speed_come_from_the_run(belt_run):
    path, belt, r = belt_run
    res = drivedyn.run(span_model(path))
    ds = xr.load_dataset(path, engine="h5netcdf")
    t = ds["time"].values
    sel = (t > 0.3) & (t <= 0.4 + 1e-12)
    ten = ds["span_tension"].sel(span="driven-driver").values[sel]
    v = abs(ds["span_speed"].sel(span="driven-driver").values[sel].mean())
    s = res.summary
    assert s["pretension"] == pytest.approx(ten.mean(), rel=1e-12)
    assert s["speed"] == pytest.approx(v, rel=1e-12)
    # the same numbers as the belt run's own summary
    assert s["pretension"] == pytest.approx(r.summary["spans"]["driven-driver"]["tension_mean"], rel=1e-9)
    L = next(sp.length for sp in compute_layout(belt).spans if sp.name == "driven-driver")
    assert s["span_length"] == pytest.approx(L, rel=1e-12)
    assert s["mass_per_length"] == belt.belt.mass_per_length
    assert s["belt_run"]["status"] == r.status and s["belt_run"]["window"] == [0.3, 0.4]
    # the tension history's mean over whole excitation periods is the span's mean tension
    assert s["tooth_force_mean"] == pytest.approx(ten.mean(), rel=0.01)
    assert 0 <= s["f1"] < ten.max() - ten.min()


def test_given_pretension_and_speed_win(belt_run):
    path, _, _ = belt_run
    res = drivedyn.run(span_model(path, operation={"pretension": 300.0, "speed": 0.5}))
    assert res.summary["pretension"] == 300.0 and res.summary["speed"] == 0.5


@pytest.mark.parametrize("span, expect", [
    ({"belt_results": "nope.nc", "span_name": "driven-driver"}, "not found"),
    ({"belt_results": "RESULTS", "span_name": "nope"}, "no span named 'nope'"),
    ({"belt_results": "RESULTS"}, "needs span.span_name"),
    ({"belt_results": "RESULTS", "span_name": "driven-driver", "length": 0.3}, "exactly one of"),
])
def test_bad_results_references_are_one_line(belt_run, span, expect):
    path, _, _ = belt_run
    span = {k: (str(path) if v == "RESULTS" else v) for k, v in span.items()}
    with pytest.raises(drivedyn.ModelError, match=expect):
        m = span_model(path)
        drivedyn.run(from_dict({**m.model_dump(mode="json", exclude_none=True), "span": span}))


def test_results_of_another_kind_are_refused(tmp_path):
    r = drivedyn.run(drivedyn.replace(drivedyn.load(drivedyn.example_path("span-t10")),
                                      {"chart.points": [8, 8], "chart.zoom.points": [4, 4], "chart.floquet": False}))
    r.save(tmp_path)
    with pytest.raises(drivedyn.ModelError, match="not the results.nc of a belt-drive run"):
        drivedyn.run(span_model(tmp_path / "results.nc"))
