"""Interference maps: a scale that starts at 0, with 0 the palest colour (an all-zero map once sat
mid-scale on -0.1..0.1, read as negative overlap)."""
import numpy as np
import xarray as xr

from drivedyn.toothed.plots import plot_maps


def _maps(area, depth):
    return xr.Dataset({"map_overlap_area": (("map_teeth", "map_pitch_error"), area),
                       "map_penetration": (("map_teeth", "map_pitch_error"), depth)},
                      coords={"map_teeth": [22, 24], "map_pitch_error": [-3e-4, 0.0, 3e-4]},
                      attrs={"title": "test pair"})


def _images(fig):
    return [ax.images[0] for ax in fig.axes if ax.images]


def _lightness(rgba):
    return float(np.dot(rgba[:3], [0.299, 0.587, 0.114]))


def test_all_zero_map_is_pale_on_a_scale_from_zero():
    fig = plot_maps(_maps(np.zeros((2, 3)), np.zeros((2, 3))))
    images = _images(fig)
    assert len(images) == 2
    for im in images:
        assert im.get_clim() == (0.0, 1.0)
        assert _lightness(im.cmap(im.norm(0.0))) > 0.85     # zero drawn pale, not mid-scale
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert texts.count("0 everywhere: no overlap") == 2
    assert all(ax.get_title() for ax in fig.axes if ax.images)


def test_map_scale_runs_from_zero_to_the_largest_value():
    area = np.array([[0.0, 2e-7, 5e-7], [0.0, 0.0, 1e-7]])      # m^2
    depth = np.array([[0.0, 1e-5, 4e-5], [0.0, 0.0, 2e-6]])     # m
    images = _images(plot_maps(_maps(area, depth)))
    assert np.allclose(images[0].get_clim(), (0.0, 0.5))       # mm^2
    assert np.allclose(images[1].get_clim(), (0.0, 0.04))      # mm
    for im in images:
        assert _lightness(im.cmap(im.norm(0.0))) > 0.85
        assert _lightness(im.cmap(im.norm(im.get_clim()[1]))) < 0.3
