"""The segment model's constant kernel records, Belt and Contact (their fields are described in
_kernels.py), and the friction law ids. No numba here: check builds them to state the time step
without importing the kernels."""
from typing import NamedTuple

import numpy as np

# friction law ids (Contact.law)
LAW_THRELFALL, LAW_ELASTIC_PLASTIC = 0, 1
LAWS = {"threlfall": LAW_THRELFALL, "elastic-plastic": LAW_ELASTIC_PLASTIC}


class Belt(NamedTuple):
    n: int
    m: np.ndarray            # segment mass (kg), eq. 2
    inertia: np.ndarray      # segment inertia about its centre (kg m^2), eq. 2 (unscaled)
    inv_m: np.ndarray        # 1 / m
    inv_i: np.ndarray        # 1 / inertia
    kax: np.ndarray          # per joint: F = kax |d|^e_L (N/m^e_L)
    bax: np.ndarray          # per joint: axial damping (N s/m)
    kb: np.ndarray           # per joint: bending stiffness (N m/rad^e_B)
    bb: np.ndarray           # per joint: bending damping (N m s/rad)
    eax: float               # e_L
    eb: float                # e_B
    linear: bool             # e_L == 1 (skips the power)
    hl: float                # half segment length (m)
    turn: float              # total turn of the closed path (rad)
    g: float                 # gravity, along -y (m/s^2)
    iscale: float            # rotation mass scaling of the semi-implicit scheme (system.ROTATION_SCALE)
    implicit: bool           # the `implicit` scheme: joints through the chain solve (_chain.py)


class Contact(NamedTuple):
    c1: np.ndarray           # per segment (N/m^2)
    c2: np.ndarray           # per segment (N/m)
    bc: np.ndarray           # per segment contact damping (N s/m)
    mu: np.ndarray           # per segment friction coefficient (friction zones)
    pmax: float              # depth of the damping ramp delta(p) (m), eq. 10
    law: int                 # LAW_THRELFALL | LAW_ELASTIC_PLASTIC
    dv: float                # Threlfall's Delta_v (m/s)
    dmax: float              # elastic-plastic displacement limit Delta_max (m)
    centre: bool             # friction read at the segment's centre (r - p), else at the contact radius r
    # a synchronous belt's teeth (segments/_teeth.py); all zero / empty for a friction belt
    tk: np.ndarray = np.zeros(0)        # per segment: its tooth's stiffness (N/m; 0: no tooth)
    tc: np.ndarray = np.zeros(0)        # per segment: its tooth's damping (N s/m)
    tplay: float = 0.0                  # sideways play of a seated tooth (m)
    tclimb: float = 0.0                 # tan(phi - rho) of the climb criterion (0: no climbing)
    tpitch: float = 0.0                 # the belt's pitch (m)
    tband: float = 0.0                  # a tooth engages within this distance outside the pitch circle (m)
    gz: np.ndarray = np.zeros(0, dtype=np.int64)   # per pulley: grooves (0: smooth)
    gphase: np.ndarray = np.zeros(0)    # per pulley: angle of groove 0 at theta = 0 (rad)
    teeth: bool = False                 # any tooth
    # non-circular pulleys (``pulleys[].pitch_curve``; segments/_curves.py): per pulley its curve's row
    # in the tables (-1: a circle) and the radius within which a segment may touch it (the contact
    # radius of a circle); per curve, tables over one turn of its own angle (uniform, periodic cubic):
    # the contact curve's radius, the pitch curve's radius, its curvature and the periodic part of
    # the arc position on it (S - perimeter phi / 2 pi), and perimeter / 2 pi
    ccur: np.ndarray = np.zeros(0, dtype=np.int64)
    creach: np.ndarray = np.zeros(0)
    crad: np.ndarray = np.zeros((0, 4))
    cpr: np.ndarray = np.zeros((0, 4))
    ckap: np.ndarray = np.zeros((0, 4))
    carc: np.ndarray = np.zeros((0, 4))
    cper: np.ndarray = np.zeros(0)


# A stage of the time loop (``_advance``) is a function of its own, compiled once, not inlined into
# the loop as numba IR: numba copies an inlined function's IR at a cost that grows with its size
# times its blocks, and then compiles one giant function (the implicit kernel: 48 s cold against
# 21 s as stages, 2-core AMD EPYC; LLVM inlines the smaller stages, the others are a call per step).
# Compiled as the loop is (no fast-math, numpy's error model, no reference counting: a stage
# allocates nothing), so every number is the same to the bit, the steps as fast, and without the
# wrappers a function called from Python needs (a record's wrapper unboxes each of its arrays:
# 1.6 s of compile for the loop's arguments alone).
STAGE = {"cache": True, "_nrt": False, "error_model": "numpy", "no_cpython_wrapper": True, "no_cfunc_wrapper": True}
STAGE_PY = {**STAGE, "no_cpython_wrapper": False}     # a stage the tests also call from Python
