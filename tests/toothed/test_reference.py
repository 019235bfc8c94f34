"""Reference tests of the meshing geometry: closed forms from the profile dimensions, symmetry,
convergence under refinement, and the seed's (Pakula, seed 001) qualitative findings."""
import numpy as np
import pytest

from drivedyn.toothed.engagement import headline, sweep
from drivedyn.mechanics.teeth.interference import Flank, evaluate
from drivedyn.mechanics.teeth.profiles import tooth_outline
from drivedyn.mechanics.teeth.pulley import pulley_polygon

from .conftest import DEG, MM, make_pair


def seated(pair):
    """Seated interference arrays and the index of the tooth tip sample."""
    flank = Flank.from_outline(tooth_outline(pair.tooth, pair.tol), pair.spacing)
    out = evaluate(flank, pulley_polygon(pair), np.array([0.0]), pair.belt_radius, pair.offset, pair.tooth.land)
    tip = int(np.argmin(np.abs(flank.uv[:, 0]) + np.abs(flank.uv[:, 1] - pair.tooth.tip)))
    return out, tip


def test_l_pair_seated_clearances_follow_from_iso_dimensions():
    # ISO 5296 L tooth (s 4.65, ht 1.91, 2beta 40) in the ISO 5294 L groove (bw 3.05, hg 2.67,
    # phi 20): flanks parallel, normal gap (bw/2 + hg tan 20 - s/2) cos 20; tip gap hg - ht.
    out, tip = seated(make_pair("L", z=20))
    assert out["area"][0] == 0.0
    flank_gap = (3.05 / 2 + 2.67 * np.tan(20 * DEG) - 4.65 / 2) * np.cos(20 * DEG) * MM
    assert out["clearance_leading"][0] == pytest.approx(flank_gap, abs=1e-8)
    assert out["clearance_trailing"][0] == pytest.approx(flank_gap, abs=1e-8)
    assert out["signed"][0, tip] == pytest.approx((2.67 - 1.91) * MM, abs=1e-8)


def test_htd8m_pair_seated_clearance_is_the_gap_of_two_arcs():
    # tooth arc R 2.46 centred 3.38 - 2.46 below the land; groove bottom arc 2.57 centred
    # 3.451 - 2.57 below the outside circle; the land sits on that circle when seated, so the
    # smallest gap is R_g - R_t - |centre offset| = hg - ht, on the tooth axis.
    out, tip = seated(make_pair("HTD8M", z=24))
    assert out["area"][0] == 0.0
    gap = (2.57 - 2.46 - abs((3.451 - 2.57) - (3.38 - 2.46))) * MM
    assert gap == pytest.approx((3.451 - 3.38) * MM)
    assert out["signed"][0, tip] == pytest.approx(gap, abs=2e-7)  # arc sampling sagitta 0.5 um
    assert out["clearance"][0] == pytest.approx(gap, abs=2e-7)


def test_t10_small_pulley_uses_the_se_groove():
    # DIN 7721-2: z <= 20 takes the SE groove (depth 2.60): tip gap 2.60 - 2.50; z >= 21 the N (3.40)
    for z, depth in ((16, 2.60), (30, 3.40)):
        out, tip = seated(make_pair("T10", z=z))
        assert out["area"][0] == 0.0
        assert out["signed"][0, tip] == pytest.approx((depth - 2.5) * MM, abs=1e-8)


@pytest.mark.parametrize("name, z", [("MXL", 20), ("XL", 16), ("L", 12), ("H", 20), ("XH", 24), ("XXH", 24),
                                     ("T2.5", 20), ("T5", 24), ("T10", 40), ("HTD3M", 20), ("HTD5M", 20),
                                     ("HTD8M", 30), ("HTD14M", 40)])
def test_every_catalogue_pair_seats_without_overlap(name, z):
    out, tip = seated(make_pair(name, z=z, tol=2e-6, spacing=5e-5))
    assert out["area"][0] == 0.0
    assert out["signed"][0, tip] > 0


def test_results_are_symmetric_in_the_angle(htd_sweep):
    # symmetric tooth and groove: the exit at +phi mirrors the entry at -phi, flanks swapped
    o = htd_sweep.out
    assert o["area"].max() > 1e-8  # there is something to compare
    np.testing.assert_allclose(o["area"], o["area"][::-1], rtol=1e-9, atol=1e-16)
    np.testing.assert_allclose(o["penetration_leading"], o["penetration_trailing"][::-1], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(o["location_leading"], o["location_trailing"][::-1], rtol=1e-9)


def test_overlap_area_converges_with_contour_refinement(htd_sweep):
    phi = htd_sweep.phi[np.argmax(htd_sweep.out["area"])]
    areas = []
    for tol in (8e-6, 2e-6, 5e-7, 1.25e-7):
        sw = sweep(make_pair("HTD8M", tol=tol), 3, half_range=abs(phi))
        areas.append(sw.out["area"][0])
    diffs = np.abs(np.diff(areas))
    # the polygon error is proportional to the chord sagitta: each 4x refinement cuts it ~4x
    assert np.all(diffs[1:] < 0.5 * diffs[:-1])
    assert diffs[-1] < 1e-2 * areas[-1]


def test_maximum_interference_converges_with_the_angle_count():
    # nested angle grids (61 -> 481): the sampled maximum can only grow, and the gains shrink
    pen = [headline(sweep(make_pair("HTD8M"), n))["max_penetration_mm"] for n in (61, 121, 241, 481)]
    assert all(b >= a for a, b in zip(pen, pen[1:]))
    assert pen[-1] - pen[1] < 5e-3 * pen[-1]  # 121 angles (the comparison table's) within 0.5 %


def test_generated_groove_does_not_interfere_with_its_own_tooth(htd_sweep):
    h = headline(sweep(make_pair("HTD8M", groove="generated"), 121))
    assert h["max_penetration_mm"] < 2e-3  # scallops and simplification, ~ 1 um
    assert headline(htd_sweep)["max_penetration_mm"] > 0.05


def test_pitch_error_map_is_even_and_grows():
    pen = [headline(sweep(make_pair("HTD8M", offset=e * MM), 61))["max_penetration_mm"] for e in (-0.2, 0, 0.2)]
    assert pen[0] == pytest.approx(pen[2], rel=1e-6)
    assert pen[2] > pen[1] + 0.1  # 0.2 mm offset against a ~0.1 mm flank gap


def test_seed_mixed_pair_interferes_little_using_part_of_the_groove_depth(htd_sweep):
    # seed 001 section 4: an L belt on an HTD pulley shows small interference but uses only part
    # of the groove height
    mixed = headline(sweep(make_pair("L", "HTD8M", z=24), 121))
    htd = headline(htd_sweep)
    assert mixed["max_overlap_area_mm2"] <= htd["max_overlap_area_mm2"]
    assert mixed["groove_depth_used"] == pytest.approx(1.91 / 3.451)
    assert mixed["groove_depth_used"] < 0.6 < 0.95 < htd["groove_depth_used"]


def _l_corner_gap_closed_form(z):
    """Smallest gap between the ISO 5296 L tooth's trailing tip fillet and the ISO 5294 groove's
    left flank line during entry, from the rack kinematics alone (no polygons, no shapely):
    the fillet centre c (tangent to the tip line and the flank) moves as x = R_b phi + u on the
    tangent y = R_b, seen from the pulley turned by phi; gap = n . (q(phi) - G) - r_a."""
    from scipy.optimize import minimize_scalar

    from drivedyn.mechanics.teeth.kinematics import to_pulley

    p, a, s, ht, ra, bw, hg, b = 9.525, 0.381, 4.65, 1.91, 0.51, 3.05, 2.67, 20 * DEG
    r_o = z * p / (2 * np.pi) - a
    tip = -a - ht
    d_fl, n_in = np.array([np.sin(b), -np.cos(b)]), np.array([np.cos(b), np.sin(b)])
    t = (tip + ra - (-a + ra * n_in[1])) / d_fl[1]
    c = np.array([-s / 2, -a]) + t * d_fl + ra * n_in
    g = np.array([-bw / 2, r_o - hg])  # bottom corner of the groove's left flank
    g_dir, g_n = np.array([-np.sin(b), np.cos(b)]), np.array([np.cos(b), np.sin(b)])

    def gap(phi):
        q = to_pulley(c[None], np.array([phi]), r_o + a)[0, 0]
        return np.dot(q - g, g_n) - ra, np.dot(q - g, g_dir)

    res = minimize_scalar(lambda f: gap(f)[0], bounds=(-0.6, 0.0), method="bounded", options={"xatol": 1e-12})
    along = gap(res.x)[1]
    # the nearest point must lie on the straight flank, between the bottom fillet (1.19 mm, 70 deg
    # turn) and the tip fillet (1.17 mm, at most 70 deg), for the line distance to be the contour's
    assert 1.19 * np.tan(35 * DEG) < along < hg / np.cos(b) - 1.17 * np.tan(35 * DEG)
    return res.fun * MM, res.x


@pytest.mark.parametrize("z", [10, 20, 30])
def test_l_pair_engagement_clearance_matches_the_closed_form(z):
    # while it enters, the L tooth's tip fillet slides past the groove flank closer than when
    # seated (0.161 mm), but never touches: the closed form and the swept polygons agree to 1 um
    gap, phi = _l_corner_gap_closed_form(z)
    sw = sweep(make_pair("L", z=z), 361)
    h = headline(sw)
    assert h["max_overlap_area_mm2"] == 0.0
    assert h["engagement"]["min_clearance_mm"] * MM == pytest.approx(gap, abs=1e-6)
    assert h["engagement"]["angle_deg"] * DEG == pytest.approx(phi, abs=2 * (sw.phi[1] - sw.phi[0]))
    assert 0.05 * MM < gap < 0.161 * MM


def test_seed_l_finding_is_not_a_property_of_the_standard_l_data(htd_sweep):
    # Seed 001 (section 5) finds that L interferes markedly more than HTD. With the ISO 5296 /
    # ISO 5294 nominal L data the unloaded L tooth never touches its groove for 10-30 teeth (the
    # closed form above), while HTD 8M overlaps by 0.069 mm: the seed's L data (not given) must
    # differ. This records the contrary result so that a change of the L data or the kinematics
    # that alters it is noticed; the README (timing-belt meshing) gives the numbers.
    for z in (10, 14, 20, 30):
        assert headline(sweep(make_pair("L", z=z), 121))["max_overlap_area_mm2"] == 0.0
    assert headline(htd_sweep)["max_penetration_mm"] == pytest.approx(0.069, abs=0.002)
