"""Reference tests of the meshing geometry: closed forms from the profile dimensions, symmetry,
convergence under refinement, and the seed's (Pakula, seed 001) qualitative findings."""
import numpy as np
import pytest

from drivedyn.toothed.engagement import headline, sweep
from drivedyn.toothed.interference import Flank, evaluate
from drivedyn.toothed.profiles import tooth_outline
from drivedyn.toothed.pulley import pulley_polygon

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


@pytest.mark.xfail(strict=True, reason="not reproduced: with the ISO 5296/5294 nominal dimensions the L "
                   "tooth has 0.16 mm flank and 0.76 mm tip clearance and never touches an unloaded "
                   "groove in the exact rack/wrap kinematics, while HTD (0.07 mm) does; see the README, timing-belt meshing")
def test_seed_l_interferes_much_more_than_htd(htd_sweep):
    l_pair = headline(sweep(make_pair("L", z=20), 121))
    assert l_pair["max_overlap_area_mm2"] > 2 * headline(htd_sweep)["max_overlap_area_mm2"]
