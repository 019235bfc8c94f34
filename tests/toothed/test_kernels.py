"""The compiled distances of the interference evaluation against GEOS (shapely), which they replace
in the hot loop: the same numbers to round-off on random polylines and points."""
import numpy as np
import shapely

from drivedyn.mechanics.teeth._kernels import nearest_distance, on_polyline


def test_points_located_on_a_polyline_as_geos_does():
    rng = np.random.default_rng(7)
    n, m = 6, 40
    # wavy polylines (a flank sampled densely) and points near and far from them
    u = np.linspace(-1, 1, m)
    pts = np.stack([np.column_stack([u, 0.3 * np.sin(3 * u + k) + 0.05 * rng.standard_normal(m)]) for k in range(n)])
    q = rng.uniform(-1.3, 1.3, (500, 2))
    which = rng.integers(0, n, 500)
    d, s = on_polyline(pts, which, q)
    lines = shapely.linestrings(pts)[which]
    vp = shapely.points(q)
    assert np.abs(d - shapely.distance(lines, vp)).max() < 1e-14
    assert np.abs(s - shapely.line_locate_point(lines, vp)).max() < 1e-12


def test_nearest_segment_distances_as_geos_gives_them():
    rng = np.random.default_rng(3)
    ring = np.column_stack([np.cos(np.linspace(0, 2 * np.pi, 300)), np.sin(np.linspace(0, 2 * np.pi, 300))])
    ring *= (1 + 0.1 * np.sin(12 * np.linspace(0, 2 * np.pi, 300)))[:, None]
    pts = rng.uniform(-1.2, 1.2, (5, 60, 2))
    d = nearest_distance(pts, np.ascontiguousarray(ring[:-1]), np.ascontiguousarray(ring[1:]), 10.0)
    geos = shapely.distance(shapely.LineString(ring), shapely.points(pts.reshape(-1, 2))).reshape(5, 60)
    assert np.abs(d - geos).max() < 1e-14
    # a margin that reaches no segment: nothing searched, +inf
    far = np.full((1, 3, 2), 5.0)
    assert np.isinf(nearest_distance(far, np.ascontiguousarray(ring[:-1]), np.ascontiguousarray(ring[1:]), 0.1)).all()
