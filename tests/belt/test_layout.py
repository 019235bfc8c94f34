"""Layout and statics against closed forms (open-belt length, hub load = vector sum of tensions)."""
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import drivedyn
from drivedyn.core.errors import ModelError
from drivedyn.belt.geometry.placement import initial_state
from drivedyn.mechanics.layout import compute_layout, layout_from
from drivedyn.belt.statics import capstan_torque


def test_open_belt_length_formula():
    # L = 2C cos(phi) + pi (D + d)/2 + phi (D - d), sin(phi) = (D - d) / 2C
    C, D, d = 0.5, 0.2, 0.1
    lay = layout_from(["a", "b"], [(0, 0), (C, 0)], [d / 2, D / 2], ["inside", "inside"])
    phi = math.asin((D - d) / (2 * C))
    assert lay.length == pytest.approx(2 * C * math.cos(phi) + math.pi * (D + d) / 2 + phi * (D - d), rel=1e-12)
    assert lay.wrap.sum() == pytest.approx(2 * math.pi)
    assert lay.wrap[0] == pytest.approx(math.pi - 2 * phi)


def test_clockwise_order_and_back_idler():
    names = ["crank", "alt", "pump", "idler"]
    C = [(0.04, -0.30), (0.16, -0.10), (0, 0), (-0.02, -0.13)]
    lay = layout_from(names, C, [0.08, 0.056, 0.027, 0.031], ["inside", "inside", "inside", "back"])
    rev = layout_from(names[::-1], C[::-1], [0.031, 0.027, 0.056, 0.08],
                      ["back", "inside", "inside", "inside"])
    assert lay.orientation == -rev.orientation
    assert lay.length == pytest.approx(rev.length, rel=1e-12)
    assert np.sum(np.sign(lay.rho) * lay.wrap) == pytest.approx(2 * math.pi * lay.orientation)


def test_static_hub_load_is_vector_sum(model_factory):
    m = model_factory()
    lay = compute_layout(m)
    H = lay.hub_load_static(500.0)
    # 180 degree wraps: 2 T along the centre line
    assert H[0] == pytest.approx([1000.0, 0.0], abs=1e-9)
    for j, w in enumerate(lay.wrap):
        assert np.hypot(*H[j]) == pytest.approx(2 * 500 * math.sin(w / 2))


def test_initial_state_at_pretension(model_factory):
    for n in (60, 150, 400):
        m = model_factory(belt__segments=n)
        init = initial_state(m, compute_layout(m))
        e = np.stack([np.cos(init.phi), np.sin(init.phi)], 1)
        P = np.stack([init.x, init.y], 1)
        d = (P - init.seg_length / 2 * e) - np.roll(P + init.seg_length / 2 * e, 1, axis=0)
        T = np.hypot(d[:, 0], d[:, 1]) * m.belt.axial_stiffness / init.seg_length
        assert T == pytest.approx(550.0, rel=1e-4)


def test_capstan_formula():
    assert capstan_torque(300, 0.027, math.pi, 0.3) == pytest.approx(2 * 300 * 0.027 * math.tanh(0.3 * math.pi / 2))


def test_check_report_lists_everything():
    text = drivedyn.check(drivedyn.example_path("belt-accessory"))
    for word in ("crankshaft", "idler", "wrap", "hub load", "f1 Hz", "alternator-idler", "measure here", "slip margin"):
        assert word in text


def _off_path(layout, p):
    """Distance of point p from the path of ``layout`` (its nearest line or arc), written here."""
    best = math.inf
    for piece in layout.pieces():
        if piece[0] == "line":
            _, a, b, L = piece
            u = min(max(np.dot(p - a, b - a) / L ** 2, 0.0), 1.0)
            best = min(best, float(np.hypot(*(a + u * (b - a) - p))))
        else:
            _, c, R, a0, sweep, _ = piece
            ang = (math.atan2(p[1] - c[1], p[0] - c[0]) - a0) * math.copysign(1, sweep) % (2 * math.pi)
            if ang <= abs(sweep) + 1e-9 or ang >= 2 * math.pi - 1e-9:
                best = min(best, abs(float(np.hypot(*(p - c))) - R))
    return best


def _check_walk(layout, n, l, g, closes):
    from drivedyn.belt.geometry.placement import _Path, _walk

    path = _Path(layout)
    S, E, s_end = _walk(path, n, l, g)
    assert np.hypot(*(E - S).T) == pytest.approx(l, rel=1e-12)
    if g > 0:
        assert np.hypot(*(np.roll(S, -1, axis=0) - E)[:-1].T) == pytest.approx(g, rel=1e-8, abs=1e-15)
    if closes:
        assert abs(s_end - path.length) < 1e-9
    assert max(_off_path(layout, p) for p in np.vstack([S, E])) < 1e-12


def test_the_placement_walk_is_exact_on_a_six_pulley_path():
    """The walk (placement._walk) on examples/fead-runup.toml's path (a back-side idler,
    a 28 mm alternator, 0.8 um gaps at 666 segments): every chord is l and every gap g to round-off,
    every chord end lies on the path (its distance to the nearest line or arc, taken here), and
    the walk closes on the path's length."""
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")), {"belt.segments": 666})
    init = initial_state(m, compute_layout(m))
    _check_walk(init.layout, 666, init.seg_length, init.gap, closes=True)


@settings(max_examples=60, deadline=None)
@given(nk=st.integers(2, 5), seed=st.integers(0, 10 ** 6), n=st.sampled_from([12, 37, 150, 700]),
       fill=st.floats(0.95, 0.999), gap=st.sampled_from([0.0, 1e-9, 1e-4, 0.02]))
def test_the_placement_walk_on_random_paths(nk, seed, n, fill, gap):
    """The same on random paths: 2-5 pulleys of 15-80 mm, one on its back, chords from 12 to 700
    to a loop, gaps from none to 2 % of a chord (a chord may span whole short pieces)."""
    rng = np.random.default_rng(seed)
    ang = 2 * np.pi * np.arange(nk) / nk + rng.uniform(-0.2, 0.2, nk)
    rad = rng.uniform(0.12, 0.3, nk)
    centers = np.stack([rad * np.cos(ang), rad * np.sin(ang)], 1)
    sides = ["back" if nk >= 4 and k == 1 else "inside" for k in range(nk)]
    try:
        lay = layout_from([f"p{k}" for k in range(nk)], centers, rng.uniform(0.015, 0.08, nk), sides)
    except ModelError:       # a back-side idler outside its span: not a drive
        assume(False)
    l = lay.length / n * fill / (1 + gap)
    _check_walk(lay, n, l, gap * l, closes=False)


@settings(max_examples=30, deadline=None)
@given(nk=st.integers(2, 5), seed=st.integers(0, 10 ** 6), n=st.sampled_from([12, 150, 700]),
       gap=st.sampled_from([0.0, 1e-9, 0.02]))
def test_the_walk_places_whole_pieces_as_the_chord_by_chord_search_does(nk, seed, n, gap):
    """The walk places the chord-and-gap pairs that lie wholly on one line or arc at once (walk.py,
    ``_whole_pairs``); chord by chord (every end searched on the path) it puts every end at the
    same point to round-off and reaches the same arc length."""
    from drivedyn.belt.geometry import walk

    rng = np.random.default_rng(seed)
    ang = 2 * np.pi * np.arange(nk) / nk + rng.uniform(-0.2, 0.2, nk)
    rad = rng.uniform(0.12, 0.3, nk)
    centers = np.stack([rad * np.cos(ang), rad * np.sin(ang)], 1)
    try:
        lay = layout_from([f"p{k}" for k in range(nk)], centers, rng.uniform(0.015, 0.08, nk), ["inside"] * nk)
    except ModelError:       # a small pulley inside its neighbours' tangent: no wrap, not a drive
        assume(False)
    from drivedyn.belt.geometry.placement import _Path

    path = _Path(lay)
    l = lay.length / n * 0.99 / (1 + gap)
    pc = path.pieces.tolist()
    S, E, s = walk.walk_pieces(pc, path.length, n, l, gap * l)
    whole = walk._whole_pairs
    try:
        walk._whole_pairs = lambda *a: (0, 0.0, 0.0, None, 0.0)      # every end searched
        S1, E1, s1 = walk.walk_pieces(pc, path.length, n, l, gap * l)
    finally:
        walk._whole_pairs = whole
    assert np.abs(S - S1).max() < 1e-12 and np.abs(E - E1).max() < 1e-12 and abs(s - s1) < 1e-12
