"""Belt plots a reader can read: a curve equal to an earlier one drawn dashed on top and named so
(the two-pulley drive's hub loads hid one another); the spectrum's peaks read as driver orders."""
import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from drivedyn.belt.plots import plot_hub_loads, plot_spectrum, twins


def _drive(t, hub_driver, hub_driven, tension, speed):
    pulleys = ["driver", "driven"]
    return xr.Dataset(
        {"hub_load": (("time", "pulley"), np.column_stack([hub_driver, hub_driven])),
         "hub_force_x": (("time", "pulley"), np.column_stack([hub_driver, -hub_driven])),
         "hub_force_y": (("time", "pulley"), np.zeros((len(t), 2))),
         "speed": (("time", "pulley"), np.column_stack([speed, speed])),
         "span_tension": (("time", "span"), np.column_stack([tension, 0.3 * tension]))},
        coords={"time": t, "pulley": pulleys, "span": ["driver-driven", "driven-driver"]},
        attrs={"steady_window": [0.0, float(t[-1])]})


def test_equal_hub_loads_drawn_dashed_on_top_and_named():
    t = np.linspace(0, 1, 501)
    h = 1060 + 5 * np.sin(2 * np.pi * 20 * t)
    ax = Figure().subplots()
    plot_hub_loads(_drive(t, h, h * (1 + 4e-4), h, -25 + 0 * t), ax=ax)
    lines = {ln.get_label().split(" ")[0]: ln for ln in ax.get_lines()}
    assert lines["driver"].get_linestyle() == "-"
    assert lines["driven"].get_linestyle() == "--" and lines["driven"].get_zorder() > lines["driver"].get_zorder()
    assert "same as driver within 0.1 %" in lines["driven"].get_label()


def test_different_curves_are_not_twins():
    t = np.linspace(0, 1, 101)
    a = 1000 + 0 * t
    assert twins({"a": a, "b": 1.05 * a}) == {}
    assert twins({"a": a, "b": 1.005 * a, "c": 1.005 * a})["b"][0] == "a"
    assert twins({"a": a, "b": 1.005 * a, "c": 1.005 * a})["c"][0] == "a"    # not chained through b


def test_spectrum_order_axis_names_the_peak_by_order():
    dt = 1e-3
    t = np.arange(4000) * dt
    fd = 4.01                                       # driver's mean speed, rev/s
    speed = -2 * np.pi * fd + 0.01 * np.sin(2 * np.pi * 86 * t)
    tension = 806 + 5 * np.sin(2 * np.pi * 86 * t) + 0.5 * np.sin(2 * np.pi * 170 * t)
    fig = Figure()
    ax = fig.subplots(3, 1)
    assert plot_spectrum(_drive(t, tension, tension, tension, speed), "driver", ax)
    (order,) = ax[0].child_axes                     # the secondary axis on top, in driver orders
    assert "order" in order.get_xlabel() and "4.01 Hz" in order.get_xlabel()
    labels = [a.get_text() for a in ax[0].texts]
    named = [float(s.split("order ")[1]) for s in labels if s.startswith("86 Hz")]
    assert len(named) == 1 and abs(named[0] - 86 / fd) < 0.06, labels     # bins 0.25 Hz apart
    assert not any(ln.get_linestyle() == ":" for ln in ax[0].get_lines())   # orders 1-6 would crowd 0-500 Hz


def test_a_drift_of_the_window_is_not_named_a_peak():
    """A tension that drifts over the steady window (a slow trend, not a vibration) leaks into the
    lowest bins of the spectrum; named, it read as a "1 Hz, order 0.0" peak in a run-up's plot."""
    dt = 1e-3
    t = np.arange(1200) * dt                        # a 1.2 s window: bins 0.83 Hz apart
    fd = 72.8
    speed = -2 * np.pi * fd + 0 * t
    tension = 677 + 40 * t / t[-1] + 8 * (t / t[-1]) ** 2 + 90 * np.sin(2 * np.pi * 146 * t)
    fig = Figure()
    ax = fig.subplots(3, 1)
    assert plot_spectrum(_drive(t, tension, tension, tension, speed), "driver", ax)
    labels = [a.get_text() for a in ax[0].texts]
    assert labels and all(float(s.split(" Hz")[0]) > 100 for s in labels), labels


def test_the_segments_passing_frequency_is_named_as_the_discretisations():
    """The segment model's polygon effect: a peak where the segments pass a point (belt speed over
    segment length) is a discretisation artefact and says so; a peak elsewhere reads as an order."""
    dt = 1e-3
    t = np.arange(2000) * dt
    fd = 4.0                                        # driver rev/s; radius 27 mm: belt at 0.6786 m/s
    n_seg, perimeter = 240, 1.2                     # 5 mm segments: they pass at 135.7 Hz
    passing = 2 * np.pi * fd * 0.027 * n_seg / perimeter
    speed = -2 * np.pi * fd + 0 * t
    tension = 800 + 0.5 * np.sin(2 * np.pi * passing * t) + 5 * np.sin(2 * np.pi * 30 * t)
    ds = _drive(t, tension, tension, tension, speed)
    ang = np.linspace(0, 2 * np.pi, n_seg, endpoint=False)
    rad = perimeter / (2 * n_seg * np.sin(np.pi / n_seg))     # a regular polygon of that perimeter
    ds = ds.assign(belt_x=(("frame", "segment"), (rad * np.cos(ang))[None]),
                   belt_y=(("frame", "segment"), (rad * np.sin(ang))[None]),
                   pulley_radius=("pulley", [0.027, 0.027]))
    fig = Figure()
    ax = fig.subplots(3, 1)
    assert plot_spectrum(ds, "driver", ax)
    labels = {s.split(" Hz")[0]: s for s in (a.get_text() for a in ax[0].texts)}
    assert "segment passing" in labels[f"{passing:.0f}"] and "discretisation" in labels[f"{passing:.0f}"], labels
    assert "order 7.5" in labels["30"], labels
