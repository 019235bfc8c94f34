"""A planetary stage's figures draw what their titles say: the load sharing of the model the
verdict reads (the lateral-torsional model's floating sun when the stage has one: gears-gearbox's
stage 1 plotted the torsional model's sun held, planet 1 at 1.04 MN against 0.73 MN, K_gamma 1.25,
under "load sharing" while its verdict read K_gamma 1.00), and modes counted on a whole-number axis."""
import matplotlib

matplotlib.use("Agg")

import numpy as np
import xarray as xr

from drivedyn.gears import plots


def _ds(lateral: bool, label="planetary"):
    planet = f"{label}_planet"
    data = {f"{label}_sun_planet_force": ((planet,), [1.04e6, 0.73e6, 0.73e6]),
            f"{label}_ring_planet_force": ((planet,), [1.0e6, 0.7e6, 0.7e6]),
            f"{label}_natural_frequency": ((f"{label}_mode",), np.linspace(10.0, 400.0, 7))}
    if lateral:
        data[f"{label}_lateral_sun_planet_force"] = ((planet,), [0.83e6] * 3)
        data[f"{label}_lateral_ring_planet_force"] = ((planet,), [0.8e6] * 3)
    return xr.Dataset(data, coords={planet: [1, 2, 3]})


def test_a_stage_with_a_lateral_model_plots_the_load_sharing_the_verdict_reads():
    import matplotlib.pyplot as plt

    for lateral, words, heights in ((True, "lateral-torsional model", [0.83e6] * 3),
                                    (False, "torsional model, the sun held", [1.04e6, 0.73e6, 0.73e6])):
        fig, axes = plt.subplots(1, 2)
        plots.plot_stage_loads(_ds(lateral), "planetary", axes)
        assert words in axes[0].get_title()
        bars = [r.get_height() for r in axes[0].patches][:3]
        assert np.allclose(bars, heights)
        fig.canvas.draw()
        ticks = [t for t in axes[1].get_xticks() if 1 <= t <= 7]
        assert ticks and all(float(t).is_integer() for t in ticks), ticks      # 1.0, 1.5, 2.0 ... before
        plt.close(fig)
