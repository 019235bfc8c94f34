"""Time-varying mesh stiffness over one mesh period, and the friction arms that go with it.

Every stiffness model becomes a pair stiffness k_pair(s) over the pair's contact, s in [0, eps)
mesh periods from the start of active profile A (s = 0) to its end E (s = eps). The mesh
stiffness at mesh position u in [0, 1) is the sum over the pairs in contact,
k(u) = sum_j k_pair(u + j) (seed 003, eq. 7 and text), tabulated on ``N_TABLE`` points.

- Cai (Cai & Hayashi 1994, as used by seed 003, eq. 7): k_pair = K [-1.8 sigma^2 + 1.8 sigma + 0.55],
  sigma = s / eps, K = k_mean / (0.85 eps). The bracket averages 0.85 over [0, 1], so the mesh
  average is k_mean (the mean mesh stiffness c_gamma b), not the single-pair maximum.
- Rectangular: k_single where one pair is in contact, k_double where two are. Without given values
  k_single = c' b and k_double = 1.75 c' b, the wave whose mean is ISO's c_gamma = c'(0.75 eps + 0.25).
- Potential energy: ``potential_energy.pair_stiffness`` at rho_1 = T1A + s p_b.
- ``engagement`` > 0 ramps a pair's stiffness in and out over that many mesh periods (smoothstep),
  standing for the gradual take-up of load by real teeth; the mean is kept.
- Helical meshes: the face is cut into thin transverse slices, each a spur pair of the transverse
  geometry carrying its share of the face width; the contact lines on the plane of action are
  inclined at the base helix angle, so the slice at axial position y runs y tan(beta_b) / p_bt mesh
  periods ahead of the slice at y = 0, and across the face the shift grows to the overlap ratio
  eps_beta. The helical mesh stiffness is the mean over the slices,
  k_h(u) = (1/eps_beta) int_0^eps_beta k_t(u + s) ds, taken in the limit of infinitely thin slices
  (exact on the table's harmonics: harmonic n is multiplied by (exp(2 pi i n eps_beta) - 1) /
  (2 pi i n eps_beta)); it is constant when eps_beta is a whole number. The friction moment per unit
  force is averaged the same way, weighted by the slices' stiffness.

Friction (after Vaishya & Singh 2001): pair j carries N_j = f k_j / k; its friction force mu N_j
acts across the line of action at the contact point, with arms rho_1 (driving gear) and
rho_2 = T1T2 - rho_1 (driven gear); the sliding velocity changes sign at the pitch point, so the
moment drives the driving gear before the pitch point (approach) and brakes it after (recess),
and the opposite on the driven gear. Tabulated as moment per unit mesh force.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import PairGeometry
from .potential_energy import pair_stiffness as pe_pair_stiffness

N_TABLE = 2048   # minimum points per mesh period
CAI_MEAN = 0.85   # mean of -1.8 s^2 + 1.8 s + 0.55 over [0, 1]


def cai_bracket(sigma):
    """Cai's normalised pair stiffness shape on sigma in [0, 1]."""
    sigma = np.asarray(sigma, dtype=float)
    return -1.8 * sigma ** 2 + 1.8 * sigma + 0.55


def _smooth(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


@dataclass(frozen=True)
class MeshTable:
    """Tabulated mesh quantities over one mesh period (u = k / N_TABLE)."""

    u: np.ndarray
    stiffness: np.ndarray        # N/m
    pairs: np.ndarray            # number of pairs in contact
    arm_driving: np.ndarray      # friction moment on the driving gear per unit mesh force and per unit mu (m)
    arm_driven: np.ndarray       # same on the driven gear (m)
    pair_s: np.ndarray           # s grid of one pair's contact (mesh periods)
    pair_k: np.ndarray           # that pair's stiffness (N/m), as tabulated
    mean: float


def slice_mean(table, eps_beta: float) -> np.ndarray:
    """(1/eps_beta) int_0^eps_beta f(u + s) ds of a table f over one period (u = k / N), exact on its
    harmonics: the face of a helical mesh as infinitely many thin transverse slices."""
    n = len(table)
    F = np.fft.rfft(table)
    h = np.arange(len(F))
    x = 2j * np.pi * h[1:] * eps_beta
    F[1:] *= (np.exp(x) - 1.0) / x
    return np.fft.irfft(F, n)


def pair_positions(u, eps):
    """Positions s = u + j of the pairs j = 0.. in contact at mesh positions ``u`` ((len(u), J) array, nan if out)."""
    J = int(np.ceil(eps)) + 1
    s = u[:, None] + np.arange(J)[None, :]
    return np.where(s < eps, s, np.nan)


def build(geo: PairGeometry, spec, iso_single: float, iso_mean: float, *, b: float, E=(206e9, 206e9),
          nu=(0.3, 0.3), r_int=(None, None), n_table: int = N_TABLE) -> MeshTable:
    """The mesh table of one mesh from its stiffness spec (``Stiffness`` model object).

    ``iso_single`` and ``iso_mean`` are ISO c' b and c_gamma b (N/m), used when no value is given.
    ``n_table`` points per period: a jump is spread over one cell, so a cell must not last longer
    than an integration step, or a stiffness jump acts like a ramp (and K_v is underestimated).
    """
    eps = geo.contact_ratio
    u = np.arange(n_table) / n_table
    s = pair_positions(u, eps)
    inside = ~np.isnan(s)
    npairs = inside.sum(axis=1)
    ss = np.nan_to_num(s)
    if spec.model == "cai":
        mean = spec.mean if spec.mean is not None else iso_mean
        K = mean / (CAI_MEAN * eps)
        kp = np.where(inside, K * cai_bracket(ss / eps), 0.0)
    elif spec.model == "rectangular":
        if spec.single is not None:
            k1, k2 = spec.single, spec.double
        else:
            k1 = iso_single if spec.mean is None else spec.mean / (0.75 * eps + 0.25)
            k2 = 1.75 * k1
        # per pair: the whole single value alone, an equal share of the double value otherwise
        share = np.where(npairs == 1, k1, k2 / 2.0)
        kp = np.where(inside, share[:, None], 0.0)
    elif spec.model == "constant":
        mean = spec.mean if spec.mean is not None else iso_mean
        kp = np.where(inside, (mean / np.maximum(npairs, 1))[:, None], 0.0)   # shared equally, sum = mean
    else:
        grid = np.linspace(0.0, eps, 161)
        rho = geo.rho_start + grid * geo.base_pitch
        kg = pe_pair_stiffness(geo, rho, b, E, nu, r_int)
        kp = np.where(inside, np.interp(ss, grid, kg), 0.0)
    if spec.model in ("cai", "constant"):
        kp *= mean / kp.sum(axis=1).mean()       # exact mean on the table grid (pair count varies on it)
    mean0 = kp.sum(axis=1).mean()
    if spec.engagement > 0:
        e = spec.engagement
        kp = kp * np.where(inside, _smooth(ss / e) * _smooth((eps - ss) / e), 0.0)
        kp *= mean0 / kp.sum(axis=1).mean()
    k = kp.sum(axis=1)
    if np.any(k <= 0):
        raise ValueError("mesh stiffness is not positive everywhere")
    share = kp / k[:, None]
    rho1 = geo.rho_start + ss * geo.base_pitch
    rho2 = geo.tangent_length - rho1
    approach = np.where(rho1 < geo.rho_pitch, 1.0, -1.0)
    arm_a = np.sum(np.where(inside, share * approach * rho1, 0.0), axis=1)
    arm_b = -np.sum(np.where(inside, share * approach * rho2, 0.0), axis=1)
    eps_b = getattr(geo, "overlap_ratio", 0.0)
    if eps_b > 0:
        # helical: the mean over thin slices (module docstring); moments averaged as k x arm
        ma, mb = slice_mean(k * arm_a, eps_b), slice_mean(k * arm_b, eps_b)
        k = slice_mean(k, eps_b)
        arm_a, arm_b = ma / k, mb / k
    # one pair's stiffness over its contact, for plots (taken along the table, pair j = 0 and 1)
    ps = np.concatenate([u, u + 1.0, u + 2.0])
    pk = np.concatenate([kp[:, 0], kp[:, 1], kp[:, 2] if kp.shape[1] > 2 else np.zeros_like(u)])
    keep = ps < eps
    return MeshTable(u=u, stiffness=k, pairs=npairs, arm_driving=arm_a, arm_driven=arm_b,
                     pair_s=ps[keep], pair_k=pk[keep], mean=float(k.mean()))
