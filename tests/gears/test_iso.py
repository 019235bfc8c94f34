"""ISO 6336-1:2006 stiffness and method B K_v against values worked by hand from the standard's formulas."""
import math

import numpy as np
import pytest

from drivedyn.gears.mesh import iso6336
from drivedyn.gears.mesh.stiffness import CAI_MEAN, cai_bracket
from drivedyn.gears.train.system import assemble

from .conftest import seed_model


def test_q_prime_seed_pair_by_hand():
    # 0.04723 + 0.15551/21 + 0.25791/57 - 0.00635*0.29 - 0.11654*0.29/21 - 0.00193*0.29
    # - 0.24188*0.29/57 + 0.00529*0.29^2 + 0.00182*0.29^2 = 0.0545168
    s = iso6336.single_pair_stiffness(21, 57, 0.29, 0.29, 1.5, 200.0)
    assert s.q_prime == pytest.approx(0.0545168, abs=2e-7)
    assert s.c_th == pytest.approx(18.3430, abs=1e-3)
    assert s.c_single == pytest.approx(18.3430 * 0.8 * 0.975, rel=1e-5)            # 14.3075
    assert s.c_gamma == pytest.approx(14.3075 * (0.75 * 1.5 + 0.25), rel=1e-4)     # 19.673
    assert s.low_load_factor == 1.0


def test_unshifted_pair_by_hand():
    # z 20/40, x = 0: q' = 0.04723 + 0.15551/20 + 0.25791/40 = 0.0614533, c'_th = 16.2725
    s = iso6336.single_pair_stiffness(20, 40, 0.0, 0.0, 1.6, 50.0)
    assert s.c_th == pytest.approx(16.2725, abs=1e-3)
    # low load 50 N/mm: (50/100)^0.25 = 0.84090
    assert s.low_load_factor == pytest.approx(0.84090, abs=1e-5)
    assert s.c_single == pytest.approx(16.2725 * 0.8 * 0.975 * 0.84090, rel=1e-4)
    assert s.c_gamma == pytest.approx(s.c_single * 1.45, rel=1e-12)
    # basic rack with h_fP = 1.4 m: C_B = 1 + 0.5 (1.2 - 1.4) = 0.9
    assert iso6336.basic_rack_factor(1.4, 20.0) == pytest.approx(0.9)
    # low contact ratio: c_gamma 10 % lower
    s2 = iso6336.single_pair_stiffness(20, 40, 0.0, 0.0, 1.1, 150.0)
    assert s2.c_gamma == pytest.approx(s2.c_single * (0.75 * 1.1 + 0.25) * 0.9)


def test_cai_bracket_averages_085():
    x = np.linspace(0, 1, 200001)
    assert np.trapezoid(cai_bracket(x), x) == pytest.approx(0.85, abs=1e-9)
    assert CAI_MEAN == 0.85
    # so the tabulated mesh stiffness averages to the given mean, not to the single-pair maximum
    s = assemble(seed_model())
    assert s.tables[0].mean == pytest.approx(449.9e6, rel=1e-3)


def test_potential_energy_against_the_seeds_finite_elements():
    """Seed 003 eqs. 1, 6: FE single-pair maximum 327.2e6 N/m, mean 449.9e6 N/m (not tuned here)."""
    m = seed_model(**{"meshes.m12.stiffness": {"model": "potential-energy"}})
    t = assemble(m).tables[0]
    assert t.pair_k.max() == pytest.approx(327.2e6, rel=0.10)
    assert t.mean == pytest.approx(449.9e6, rel=0.10)


def test_method_b_regions():
    mb = iso6336.MethodB(z1=21, c_single=14.0, c_gamma=19.0, m_red=0.005, eps_gamma=1.5, load_per_width=150.0,
                         f_pb=10.0, f_falpha=10.0, material="Eh", sigma_hlim=1500.0, c_a=None, pitch_radius=0.026)
    nE = mb.resonance_speed
    # n_E1 = 30000/(pi z1) sqrt(c_gamma/m_red) / 60 rev/s
    assert nE == pytest.approx(30000 / (math.pi * 21) * math.sqrt(19.0 / 0.005) / 60)
    assert mb.kv(1e-6 * nE)[0] == pytest.approx(1.0, abs=1e-5)
    assert mb.kv(0.5 * nE)[2] == "subcritical"
    assert mb.kv(1.0 * nE)[2] == "main resonance"
    # eq. 22 joins eqs. 20 and 21 continuously
    assert mb.kv(1.15 * nE * (1 + 1e-9))[0] == pytest.approx(mb.kv(1.15 * nE)[0], rel=1e-6)
    assert mb.kv(1.5 * nE * (1 - 1e-9))[0] == pytest.approx(mb.kv(1.5 * nE)[0], rel=1e-6)
    # hand: y_p = y_f = 0.075*10 = 0.75 um; C_ay = (1500/97 - 18.45)^2/18 + 1.5 = (-2.98608)^2/18 + 1.5 = 1.99538 um
    # B_p = B_f = 14*9.25/150 = 0.863333, B_k = |1 - 14*1.99538/150| = 0.813765
    # main resonance: 0.32*0.863333 + 0.34*0.863333 + 0.90*0.813765 + 1 = 2.302189
    assert mb.kv(1.0 * nE)[0] == pytest.approx(2.302189, abs=2e-6)
