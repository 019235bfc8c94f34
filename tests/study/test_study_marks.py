"""Study plots: cases that warned are marked and kept out of the colour scale (they must not swamp
the range of the valid cases, as two gross-slip cases at slip 0.7-0.8 did to slips of 0.1-0.8 %)."""
import numpy as np
import xarray as xr

from drivedyn.study.plots import plot_key


def _grid(status):
    pre, tq = [200.0, 400.0], [5.0, 10.0, 15.0]
    slip = np.array([[0.002, 0.004, 0.68], [0.001, 0.002, 0.003]])
    return xr.Dataset(
        {"slip": (("pre", "tq"), slip), "status": (("pre", "tq"), np.array(status, dtype=object))},
        coords={"pre": pre, "tq": tq}, attrs={"parameters": "pre, tq", "title": "t"})


def test_warned_case_marked_and_out_of_the_colour_scale():
    ds = _grid([["success", "success", "warning"], ["success", "success", "failed"]])
    fig = plot_key(ds, "slip")
    ax = fig.axes[0]
    mesh = ax.collections[0]
    assert mesh.get_clim()[1] == 0.004                    # the 0.68 of the warned case is not on the scale
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(lab.startswith("warning") for lab in labels) and "failed" in labels
    marks = {ln.get_label(): (ln.get_xdata().tolist(), ln.get_ydata().tolist()) for ln in ax.lines}
    warn = next(v for k, v in marks.items() if k.startswith("warning"))
    assert warn == ([15.0], [200.0])


def test_line_plot_marks_warned_case():
    ds = _grid([["success", "success", "warning"], ["success"] * 3]).isel(pre=0, drop=True)
    ds.attrs["parameters"] = "tq"
    fig = plot_key(ds, "slip")
    line = fig.axes[0].lines[0]
    assert np.isnan(line.get_ydata()[2]) and np.nanmax(line.get_ydata()) == 0.004
