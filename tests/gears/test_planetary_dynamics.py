"""Time integration of a planetary stage (drivedyn.gears.planetary.dynamics): K_v of every mesh against
references written here: the constant-stiffness limit (K_v = 1), a one-planet stage with the carrier
held against the same gears as a parallel train (the gear-train code's sweep), the quasi-static limit
(linear solves over one mesh period with the stiffness shape written out here), the resonance at the
stage's rotational mode, the planets' symmetry, and the standard-gear phase of a planet's two meshes."""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.gears.planetary import dynamics as pd
from drivedyn.core.model import from_dict

M = 3e-3
ALPHA = math.radians(20)


def stage_model(dynamics=None, **kw):
    pl = {"sun_teeth": 24, "planet_teeth": 24, "module": M, "planets": 4, "sun_planet_stiffness": 4e8,
          "ring_planet_stiffness": 5e8, "sun_inertia": 2e-3, "ring_inertia": 0.3, "carrier_inertia": 0.05,
          "planet_inertia": 1e-3, "planet_mass": 0.6, "fixed": "ring", "input": "sun", "torque": 300.0,
          "dynamics": {"speed": 300.0, **(dynamics or {})}}
    pl.update(kw)
    return from_dict({"kind": "gear-train", "planetary": pl})


def run(model):
    return pd.run(model.planetary)


def test_constant_stiffness_gives_kv_one():
    # no stiffness variation, no excitation: the stage turns rigidly at its static deflection, every mesh
    # force stays at its static value (with a pin error too: unequal, but constant); the quasi-static load
    # sharing is the closed form of the torsional model (ring held, carrier the output):
    # F_n = T / (N r_bs) + k_e 2 cos(alpha) (mean(e) - e_n), k_e = k_sp k_rp / (k_sp + k_rp)
    rbs = 0.5 * 24 * M * math.cos(ALPHA)
    k_e = 4e8 * 5e8 / 9e8
    for errors in ([], [20e-6, 0.0, -5e-6, 0.0]):
        s, a = run(stage_model({"stiffness_model": "constant"}, position_errors=errors))
        kv = np.array(s["kv_sun_planet"] + s["kv_ring_planet"])
        assert kv == pytest.approx(1.0, abs=1e-9)
        assert np.array(s["force_max_over_nominal_sun_planet"]) == pytest.approx(1.0, abs=1e-9)
        assert np.ptp(a["force"], axis=0).max() < 1e-9 * a["force"].max()
        e = np.r_[errors, np.zeros(4 - len(errors))]
        F = 300.0 / (4 * rbs) + k_e * 2 * math.cos(ALPHA) * (e.mean() - e)
        for key in ("load_sharing_quasi_static_sun_planet", "load_sharing_quasi_static_ring_planet"):
            assert s[key] == pytest.approx(F / F.mean(), rel=1e-9)
        assert s["force_quasi_static_max_sun_planet"] == pytest.approx(F, rel=1e-9)


def test_planet_phase_of_standard_gears_closed_form():
    # standard gears: a planet's ring-mesh and sun-mesh pitch-point passages are in phase for an odd
    # planet tooth count, half a period apart for an even one (half tooth angle pi / 2 z_p on both sides)
    for zp in (23, 24):
        m = stage_model(planet_teeth=zp, sun_teeth=25 if zp == 23 else 24)
        sun, ring, u_rs = pd.mesh_geometry(m.planetary)
        p_b = math.pi * M * math.cos(ALPHA)
        # the pitch point's place in each mesh cycle, written out: sun-planet from the sun's tangent point
        zs = m.planetary.sun_teeth
        zr = zs + 2 * zp
        rb = [0.5 * z * M * math.cos(ALPHA) for z in (zs, zp, zr)]
        ra = [0.5 * zs * M + M, 0.5 * zp * M + M, 0.5 * zr * M - M]
        a = 0.5 * (zs + zp) * M
        t_s, t_r = a * math.sin(ALPHA), a * math.sin(ALPHA)
        s_cs = (rb[0] * math.tan(ALPHA) - (t_s - math.sqrt(ra[1] ** 2 - rb[1] ** 2))) / p_b
        s_cr = (rb[1] * math.tan(ALPHA) - (math.sqrt(ra[2] ** 2 - rb[2] ** 2) - t_r)) / p_b
        delta = 0.0 if zp % 2 else 0.5
        assert (u_rs - (s_cr - s_cs - delta)) % 1.0 == pytest.approx(0.0, abs=1e-12) or \
            (u_rs - (s_cr - s_cs - delta)) % 1.0 == pytest.approx(1.0, abs=1e-12)
        # contact ratios: the path of contact over the base pitch, external and internal
        eps_s = (math.sqrt(ra[0] ** 2 - rb[0] ** 2) + math.sqrt(ra[1] ** 2 - rb[1] ** 2) - t_s) / p_b
        eps_r = (math.sqrt(ra[1] ** 2 - rb[1] ** 2) - math.sqrt(ra[2] ** 2 - rb[2] ** 2) + t_r) / p_b
        assert (sun.contact_ratio, ring.contact_ratio) == pytest.approx((eps_s, eps_r), rel=1e-12)


def _tip_for_contact_ratio(z_p, z_x, eps):
    """Tip radius of an external gear of z_x teeth that gives contact ratio ``eps`` with the planet."""
    rb_p, rb_x = 0.5 * z_p * M * math.cos(ALPHA), 0.5 * z_x * M * math.cos(ALPHA)
    ra_p = 0.5 * z_p * M + M
    a = 0.5 * (z_p + z_x) * M
    p_b = math.pi * M * math.cos(ALPHA)
    root = eps * p_b + a * math.sin(ALPHA) - math.sqrt(ra_p ** 2 - rb_p ** 2)
    return math.sqrt(root ** 2 + rb_x ** 2)


def test_one_planet_with_the_carrier_held_is_a_train_of_three_gears():
    # carrier held, one planet: sun -> planet -> ring is a train of fixed axes, the ring an internal gear.
    # The gear-train code integrates the same equations with an external gear for the ring whose tip gives
    # the internal mesh's contact ratio (the stiffness shape is a function of the contact ratio only), the
    # ring mesh's phase the stage's, and the same steps, settling and window: K_v must agree
    zs, zp, zr = 20, 31, 82
    speeds = [150.0, 900.0, 2600.0]
    dyn = {"speed": speeds[0], "damping_ratio": 0.05, "sweep": True, "speed_min": speeds[0], "speed_max": speeds[-1],
           "count": 3, "settle": 0.02, "window_cycles": 30, "steps_per_cycle": 64, "step": 2e-6}
    stage = stage_model(dyn, sun_teeth=zs, planet_teeth=zp, planets=1, fixed="carrier", input="sun",
                        sun_inertia=2e-3, planet_inertia=4e-3, ring_inertia=0.3)
    sys_ = pd.system(stage.planetary)
    s, a = pd.run(stage.planetary)
    kv_stage = a["kv_sweep"]
    _, ring, u_rs = pd.mesh_geometry(stage.planetary)
    speeds_run = a["sweep_speed"]
    assert speeds_run == pytest.approx(np.linspace(speeds[0], speeds[-1], 3))
    tip = _tip_for_contact_ratio(zp, zr, ring.contact_ratio)
    common = {"module": M, "face_width": 0.03}
    train = from_dict({
        "kind": "gear-train",
        "gears": [{"name": "sun", "teeth": zs, "inertia": 2e-3, **common},
                  {"name": "planet", "teeth": zp, "inertia": 4e-3, **common},
                  {"name": "ring", "teeth": zr, "inertia": 0.3, "tip_diameter": 2 * tip, "load_fraction": 1.0, **common}],
        "meshes": [{"name": "sp", "gears": ["sun", "planet"], "damping_ratio": 0.05, "phase": 0.0,
                    "stiffness": {"model": "cai", "mean": 4e8}},
                   {"name": "rp", "gears": ["planet", "ring"], "damping_ratio": 0.05, "phase": u_rs,
                    "stiffness": {"model": "cai", "mean": 5e8}}],
        "drive": {"input": "sun", "speed": speeds[0], "torque": 300.0},
        "simulation": {"step": 2e-6, "duration": 0.01},
        "sweep": {"enabled": True, "speed_min": speeds[0], "speed_max": speeds[-1], "count": 3, "settle": 0.02,
                  "window_cycles": 30, "steps_per_cycle": 64},
        "iso": {"rating": False}})
    from drivedyn.gears.train.sweep import run_sweep
    from drivedyn.gears.train.system import assemble

    tsys = assemble(train)
    assert tsys.pairs[1].contact_ratio == pytest.approx(ring.contact_ratio, rel=1e-12)
    assert tsys.damping == pytest.approx(sys_.damping, rel=1e-12)
    assert tsys.force_nominal == pytest.approx(s["force_nominal_sun_planet"] + s["force_nominal_ring_planet"], rel=1e-12)
    sw = run_sweep(tsys, train)
    print(kv_stage, sw["kv"])
    assert kv_stage == pytest.approx(sw["kv"], rel=2e-4)
    assert np.ptp(kv_stage) > 0.05          # the speeds differ in K_v: the comparison is not of constants


def _cai_mesh(u, eps, engagement):
    """Cai's mesh stiffness shape with smoothstep engagement at mesh positions u (unnormalised)."""
    def smooth(x):
        x = np.clip(x, 0.0, 1.0)
        return x * x * (3 - 2 * x)

    k = np.zeros_like(u)
    for j in range(math.ceil(eps) + 1):
        s = u + j
        inside = s < eps
        sig = s / eps
        k += np.where(inside, (-1.8 * sig ** 2 + 1.8 * sig + 0.55) * smooth(s / engagement)
                      * smooth((eps - s) / engagement), 0.0)
    return k


def _quasi_static_reference(m, zs, zp, N, eng, points=2000):
    """Largest quasi-static mesh forces over one mesh period (ring and carrier held, 300 N m on the sun):
    linear solves with the stiffness shape and the torsional stiffness matrix written out, sequential
    phasing by the counting rule."""
    sun, ring, u_rs = pd.mesh_geometry(m.planetary)
    zr = zs + 2 * zp
    rbs, rbp = (0.5 * z * M * math.cos(ALPHA) for z in (zs, zp))
    grid = np.arange(200000) / 200000
    mean_s = _cai_mesh(grid, sun.contact_ratio, eng).mean()
    mean_r = _cai_mesh(grid, ring.contact_ratio, eng).mean()
    psi = 2 * math.pi * np.arange(N) / N
    g_s = (zs * psi / (2 * math.pi)) % 1.0
    g_r = (-zr * psi / (2 * math.pi)) % 1.0
    T = 300.0
    fmax = np.zeros(2 * N)
    for u in np.arange(points) / points:
        ks = 4e8 * _cai_mesh(np.atleast_1d((u - g_s) % 1.0), sun.contact_ratio, eng) / mean_s
        # the planets' ring meshes follow their sun meshes at u_rs - gamma_rn + gamma_sn
        kr = 5e8 * _cai_mesh(np.atleast_1d((u + u_rs - g_r) % 1.0), ring.contact_ratio, eng) / mean_r
        # coordinates sun, planet 1..N (ring and carrier held): sun-planet d = rbs th_s + rbp th_n,
        # ring-planet d = -rbp th_n
        K = np.zeros((1 + N, 1 + N))
        for n in range(N):
            a = np.zeros(1 + N)
            a[0], a[1 + n] = rbs, rbp
            b = np.zeros(1 + N)
            b[1 + n] = -rbp
            K += ks[n] * np.outer(a, a) + kr[n] * np.outer(b, b)
        q = np.linalg.solve(K, np.r_[T, np.zeros(N)])
        f = np.r_[ks * (rbs * q[0] + rbp * q[1:]), kr * (-rbp * q[1:])]
        fmax = np.maximum(fmax, f)
    return fmax, T / (N * rbs)


def test_low_speed_kv_is_one_and_the_load_shift_is_the_quasi_static_load_sharing():
    # far below the modes (sun at 5 rad/s: mesh 11.5 Hz, modes from 3.8 kHz; smooth engagement) the mesh
    # forces follow the static load sharing of the time-varying stiffnesses, which moves load between the
    # planets (sun held on its axis): K_v, the largest force over the largest quasi-static force, tends
    # to 1; the quasi-static forces and shares are the reference's linear solves; the largest force over
    # the static force with mean stiffnesses (K_v before the two were separated) is their product
    zs, zp, N = 25, 23, 4
    eng = 0.2
    m = stage_model({"speed": 5.0, "engagement": eng, "window_cycles": 12, "settle": 0.05}, sun_teeth=zs,
                    planet_teeth=zp, planets=N)
    s, _ = run(m)
    fmax, f_nom = _quasi_static_reference(m, zs, zp, N, eng)
    kv = np.array(s["kv_sun_planet"] + s["kv_ring_planet"])
    qs = np.array(s["force_quasi_static_max_sun_planet"] + s["force_quasi_static_max_ring_planet"])
    share = np.array(s["load_sharing_quasi_static_sun_planet"] + s["load_sharing_quasi_static_ring_planet"])
    old = np.array(s["force_max_over_nominal_sun_planet"] + s["force_max_over_nominal_ring_planet"])
    print(kv - 1, qs / fmax - 1, share, fmax / f_nom)
    assert s["force_nominal_sun_planet"] == pytest.approx([f_nom] * N, rel=1e-9)
    assert kv == pytest.approx(1.0, abs=2e-5)
    # the reference's mesh positions are rigid; the run's include the elastic deflections (about 8e-4 of a
    # base pitch), which shift the meshes' stiffnesses against one another by a little
    assert qs == pytest.approx(fmax, rel=2e-4)
    assert share == pytest.approx(fmax / f_nom, rel=2e-4)          # no pin errors: the mean share is T / (N r_bs)
    assert old == pytest.approx(fmax / f_nom, rel=2e-4)
    assert (fmax / f_nom).min() > 1.25          # the stiffness variation moves load between the planets


def test_sweep_peaks_at_the_rotational_mode_of_an_in_phase_stage():
    # planets in phase (z_s / N whole): the mesh excitation drives the rotational modes, not the planet
    # modes (Parker, J. Sound Vib. 236 (2000) 561-573); the K_v sweep of both meshes peaks where the mesh
    # frequency meets the lowest rotational mode, and passes the planet mode without a peak
    from drivedyn.gears.planetary import stage as tors

    base = stage_model()
    st = tors.stage_of(base.planetary)
    f, _, _, kinds = tors.modes(st)
    rot = [fi for fi, k in zip(f, kinds) if k == "rotational" and fi > 1.0]
    planet = [fi for fi, k in zip(f, kinds) if k == "planet"]
    per = 24 * (1 - 1 / (1 + 72 / 24)) / (2 * math.pi)        # mesh Hz per rad/s of the sun: z_s (w_s - w_c) / 2 pi
    dyn = {"sweep": True, "engagement": 0.2}
    s, a = run(stage_model({**dyn, "count": 45, "speed_min": 0.88 * rot[0] / per, "speed_max": 1.16 * rot[0] / per}))
    assert s["sweep"]["mesh_hz_per_rad_s"] == pytest.approx(per, rel=1e-12)
    kv = a["kv_sweep"]
    f_mesh = a["sweep_speed"] * per
    peaks = [f_mesh[np.argmax(kv[:, :4].max(axis=1))], f_mesh[np.argmax(kv[:, 4:].max(axis=1))]]
    print(rot, planet, peaks, kv.max())
    assert peaks == pytest.approx([rot[0]] * 2, rel=0.015)
    assert kv.max() > 2.5
    s, a = run(stage_model({**dyn, "count": 21, "speed_min": 0.9 * planet[0] / per, "speed_max": 1.1 * planet[0] / per}))
    for k in (a["kv_sweep"][:, :4].max(axis=1), a["kv_sweep"][:, 4:].max(axis=1)):
        print(k)
        assert k[1:-1].max() < max(k[0], k[-1])         # no peak inside: the planet mode is not excited


def test_equally_spaced_identical_planets_have_equal_kv():
    # sequential phasing: each planet's meshes are the first planet's shifted in time by its phase, so
    # over a window of whole mesh periods every planet reaches the same largest force
    s, _ = run(stage_model({"window_cycles": 40}, sun_teeth=25, planet_teeth=23))
    for key in ("kv_sun_planet", "kv_ring_planet"):
        assert s[key] == pytest.approx([s[key][0]] * 4, rel=2e-3)


def test_carrier_input_loads_the_other_flanks_and_gives_the_same_quasi_static_kv():
    # carrier in, sun out: the static forces load the other flanks; the stage is integrated as its mirror
    # image. Far below the modes the direction of rotation does not matter: K_v as with the sun driving
    dyn = {"speed": 20.0, "engagement": 0.2, "window_cycles": 12, "settle": 0.05}
    sun_in = run(stage_model(dyn, sun_teeth=25, planet_teeth=23))[0]
    w_c = 20.0 / (1 + 71 / 25)                    # the same mesh frequency: carrier speed w_s / (1 + z_r / z_s)
    carrier_in = run(stage_model({**dyn, "speed": w_c}, sun_teeth=25, planet_teeth=23, input="carrier",
                                 torque=300.0 * (1 + 71 / 25)))[0]
    assert not sun_in["other_flanks"] and carrier_in["other_flanks"]
    assert carrier_in["mesh_frequency_hz"] == pytest.approx(sun_in["mesh_frequency_hz"], rel=1e-12)
    assert carrier_in["force_nominal_sun_planet"] == pytest.approx(sun_in["force_nominal_sun_planet"], rel=1e-9)
    for key in ("kv_sun_planet", "kv_ring_planet", "load_sharing_quasi_static_sun_planet",
                "load_sharing_quasi_static_ring_planet", "force_max_over_nominal_sun_planet"):
        assert carrier_in[key] == pytest.approx(sun_in[key], rel=2e-4)
    const = run(stage_model({**dyn, "speed": w_c, "stiffness_model": "constant", "engagement": 0.0}, sun_teeth=25, planet_teeth=23,
                            input="carrier", torque=300.0 * (1 + 71 / 25)))[0]
    assert const["kv_sun_planet"] + const["kv_ring_planet"] == pytest.approx([1.0] * 8, abs=1e-9)


def _alone_with_dynamics(rating_kv="run"):
    """Stage 1 of examples/gears-gearbox.toml alone, K_v not given, integrated at its rating's speed."""
    good = drivedyn.load(drivedyn.example_path("gears-gearbox"))
    rating = good.planetary.rating.model_copy(update={"dynamic_factors": None})
    stage = good.planetary.model_copy(update={"output_gear": None, "output_shaft_stiffness": None, "rating": rating})
    m = good.model_copy(update={"gears": [], "meshes": [], "drive": None, "planetary": stage, "stages": []})
    return drivedyn.replace(m, {"planetary.dynamics": {"rating_kv": rating_kv}})


def test_the_rating_takes_kv_from_the_run():
    # K_Hbeta, K_Halpha and K_gamma given: sigma_H goes with sqrt(K_v) and sigma_F with K_v (ISO 6336-2/-3),
    # so the rating with the run's K_v is the method B rating scaled by the ratio of the two
    run_ = drivedyn.run(_alone_with_dynamics("run")).summary["planetary"]
    mb = drivedyn.run(_alone_with_dynamics("method-b")).summary["planetary"]
    assert "dynamics" in run_ and "dynamics" in mb
    for mesh, key in (("sun-planet", "sun-planet"), ("ring-planet", "ring-planet")):
        e, b = run_["rating"]["meshes"][mesh], mb["rating"]["meshes"][mesh]
        kv = max(run_["dynamics"]["kv"][key], 1.0)
        assert e["K_v_source"] == "time integration" and b["K_v_source"] == "ISO 6336-1 method B"
        assert e["K_v"] == pytest.approx(kv, rel=1e-12) and e["K_v_method_b"] == pytest.approx(b["K_v"], rel=1e-12)
        for gear in (e["pinion"], e["wheel"]):
            assert e[gear]["sigma_H"] == pytest.approx(b[gear]["sigma_H"] * math.sqrt(kv / b["K_v"]), rel=1e-9)
            if e[gear]["sigma_F"] is not None:
                assert e[gear]["sigma_F"] == pytest.approx(b[gear]["sigma_F"] * kv / b["K_v"], rel=1e-9)
    assert run_["rating"]["K_v_note"].startswith("from the time integration")
    assert "rating_kv" in mb["rating"]["K_v_note"]
    # a check does not integrate: it says the run will, and rates with method B
    text = drivedyn.check(_alone_with_dynamics("run"))
    assert "`drivedyn run` integrates the torsional model" in text and "ISO 6336-1 method B" in text


def test_nrel_stage_one_alone_kv_tends_to_one_below_its_modes():
    # NREL GRC stage 1 (the sun held on its axis in the torsional model, a 50 um pin error) at its rating
    # speed, 12.1 rpm of the carrier: mesh frequency z_r f_c = 56 x 12.1 / 60 = 11.29 Hz (ring held), 14.5 times below
    # its lowest mode. With a smooth engagement the forces follow the quasi-static ones (K_v -> 1), while the
    # planets pass load between them; the product K_v x quasi-static force / static force is the largest
    # force over the static one (the K_v of before). With a stiffness that steps (engagement 0) every step
    # excites the modes: K_v holds that step response, as a gear train's does at any speed
    m = drivedyn.replace(_alone_with_dynamics("method-b"), {"planetary.dynamics": {"engagement": 0.1}})
    s, _ = pd.run(m.planetary)
    assert s["mesh_frequency_hz"] == pytest.approx(56 * 12.1 / 60, rel=1e-9)
    assert s["mesh_frequency_hz"] < s["natural_frequencies_hz"][0] / 14
    print(s["kv"], s["load_sharing_factor_quasi_static"], s["force_max_over_nominal_sun_planet"])
    for key in ("sun-planet", "ring-planet"):
        assert 1.0 <= s["kv"][key] < 1.005
        assert s["load_sharing_factor_quasi_static"][key] > 1.4       # the planets pass load between them
    for mesh in ("sun_planet", "ring_planet"):
        assert np.array(s[f"force_max_over_nominal_{mesh}"]) == pytest.approx(
            np.array(s[f"kv_{mesh}"]) * np.array(s[f"force_quasi_static_max_{mesh}"])
            / np.array(s[f"force_nominal_{mesh}"]), rel=1e-12)
    steps = pd.run(drivedyn.replace(m, {"planetary.dynamics": {"engagement": 0.0}}).planetary)[0]
    assert min(steps["kv"].values()) > 1.2


LATERAL = {"sun_mass": 0.5, "ring_mass": 5.0, "carrier_mass": 3.0, "planet_bearing_stiffness": 5e8,
           "sun_bearing_stiffness": 0.0}


def test_lateral_three_planets_floating_sun_share_equally_at_every_instant():
    # a floating sun on three planets is statically determinate: its two translations and its rotation
    # balance the three sun-planet forces, whose lines of action are 120 deg apart, so each carries
    # T / (3 r_bs) whatever the pin errors and the instant's mesh stiffnesses; each planet's moment balance
    # (its pin carries no moment) makes its ring force equal to its sun force. So the quasi-static shares are
    # 1 at every instant and, far below the modes, the largest force is the static one (K_v -> 1); the
    # torsional model (sun held on its axis) shifts load between the planets instead
    rbs = 0.5 * 25 * M * math.cos(ALPHA)
    dyn = {"speed": 5.0, "engagement": 0.2, "window_cycles": 12, "settle": 0.2}
    lat = run(stage_model({**dyn, "model": "lateral"}, sun_teeth=25, planet_teeth=23, planets=3,
                          position_errors=[5e-6, 0.0, 0.0], lateral=LATERAL))[0]
    tor = run(stage_model(dyn, sun_teeth=25, planet_teeth=23, planets=3, position_errors=[5e-6, 0.0, 0.0],
                          lateral=LATERAL))[0]
    print(lat["kv"], lat["force_max_over_nominal_sun_planet"], tor["load_sharing_factor_quasi_static"])
    assert lat["model"].startswith("lateral-torsional") and tor["model"].startswith("torsional")
    for mesh in ("sun_planet", "ring_planet"):
        assert lat[f"force_nominal_{mesh}"] == pytest.approx([300.0 / (3 * rbs)] * 3, rel=1e-9)
        assert lat[f"load_sharing_quasi_static_{mesh}"] == pytest.approx([1.0] * 3, abs=1e-9)
        assert lat[f"force_quasi_static_max_{mesh}"] == pytest.approx([300.0 / (3 * rbs)] * 3, rel=1e-9)
        assert lat[f"kv_{mesh}"] == pytest.approx([1.0] * 3, abs=2e-4)
        assert lat[f"force_max_over_nominal_{mesh}"] == pytest.approx([1.0] * 3, abs=2e-4)
    assert tor["load_sharing_factor_quasi_static"]["sun-planet"] > 1.3


def test_lateral_constant_stiffness_is_the_static_lateral_load_sharing():
    # constant mesh stiffnesses, four planets, a floating sun and a pin error: the run turns rigidly at
    # the static deflection of the lateral-torsional model (Lin & Parker's load sharing, the output held:
    # planetary_lateral), its forces constant (K_v = 1); the opposite planet shares the error
    from drivedyn.gears.planetary import stage as tors
    from drivedyn.gears.planetary import lateral as pl

    m = stage_model({"stiffness_model": "constant", "model": "lateral"}, sun_teeth=25, planet_teeth=23,
                    position_errors=[8e-6, 0.0, 0.0, 0.0], lateral=LATERAL)
    s, _ = run(m)
    st = tors.stage_of(m.planetary)
    ref = pl.load_sharing(tors.lateral_stage(m.planetary, st, {"ring": "fixed", "carrier": "fixed"}), 300.0, "sun")
    print(s["force_nominal_sun_planet"], ref["sun_planet_force"])
    for mesh in ("sun_planet", "ring_planet"):
        assert s[f"force_nominal_{mesh}"] == pytest.approx(ref[f"{mesh}_force"], rel=1e-9)
        assert s[f"force_max_{mesh}"] == pytest.approx(ref[f"{mesh}_force"], rel=1e-9)
        assert s[f"kv_{mesh}"] == pytest.approx([1.0] * 4, abs=1e-9)
    f = np.array(s["force_nominal_sun_planet"])
    assert f[0] == pytest.approx(f[2], rel=1e-9) and f[1] == pytest.approx(f[3], rel=1e-9) and f[1] > 1.3 * f[0]


def test_lateral_sweep_peaks_at_the_translational_mode():
    # sequential phasing with z_s - 1 = 24 a multiple of N = 4: the fundamental mesh harmonic drives the
    # translational modes (Parker, J. Sound Vib. 236 (2000) 561-573); the lateral model's K_v sweep peaks
    # where the mesh frequency meets the lowest translational mode, which the torsional model has not
    from drivedyn.gears.planetary import stage as tors
    from drivedyn.gears.planetary import lateral as pl

    base = stage_model({"model": "lateral"}, sun_teeth=25, planet_teeth=23, lateral=LATERAL)
    st = tors.stage_of(base.planetary)
    f, _, _, kinds = pl.modes(tors.lateral_stage(base.planetary, st, {"ring": "fixed"}))
    trans = [fi for fi, k in zip(f, kinds) if k == "translational"]
    per = 25 * (1 - 1 / (1 + 71 / 25)) / (2 * math.pi)
    dyn = {"sweep": True, "engagement": 0.2, "count": 41, "speed_min": 0.86 * trans[0] / per,
           "speed_max": 1.17 * trans[0] / per}
    peaks, top = [], []
    for model in ("lateral", "torsional"):
        _, a = run(stage_model({**dyn, "model": model}, sun_teeth=25, planet_teeth=23, lateral=LATERAL))
        kv = a["kv_sweep"]
        f_mesh = a["sweep_speed"] * per
        peaks.append([f_mesh[np.argmax(kv[:, :4].max(axis=1))], f_mesh[np.argmax(kv[:, 4:].max(axis=1))]])
        top.append(kv.max())
    print(trans[:2], peaks, top)
    assert trans[0] == pytest.approx(trans[1], rel=1e-9)          # a pair, as Lin & Parker find
    assert peaks[0] == pytest.approx([trans[0]] * 2, rel=0.008)
    assert top[0] > 3.0 and top[1] < 1.5


def test_lateral_run_of_one_stage_writes_its_plots(tmp_path):
    # a single stage with [lateral] integrated in its lateral-torsional model: the overview names the model
    # and the plots are written (the lateral load sharing's arrays are no stage of their own)
    m = drivedyn.load(drivedyn.example_path("gears-planetary"))
    m = drivedyn.replace(m, {"planetary.dynamics": {"model": "lateral", "speed": 50 * math.pi},
                             "planetary.lateral": {"sun_mass": 0.6, "ring_mass": 6.0, "carrier_mass": 4.0,
                                                   "planet_bearing_stiffness": 6e8, "sun_bearing_stiffness": 0.0}})
    res = drivedyn.run(m)
    assert res.summary["planetary"]["dynamics"]["model"].startswith("lateral-torsional")
    from drivedyn.api import plot

    names = sorted(p.name for p in plot(res, tmp_path))
    assert names == ["gears-planetary-kv.png", "gears-planetary.png"]


@pytest.mark.parametrize("edit, expect", [
    (('sweep = true ', 'rating_kv = "run"\n[planetary.rating]\nface_width = "30 mm"\nspeed = "1000 rpm"\n# '),
     "dynamics.speed: the rating takes K_v from the run at its own speed"),
    (('speed = "1500 rpm"                   # the sun (input)', ''), "dynamics.speed: give the input member's speed"),
    (('stiffness_model = "cai"', 'stiffness_model = "potential-energy"'), "planetary.dynamics.stiffness_model"),
    (("damping_ratio = 0.05", "damping_ratio = 1.5"), "planetary.dynamics.damping_ratio: must lie in [0, 1)"),
    (("sweep = true ", "count = 1\nsweep = true "), "count must lie in 2..10000"),
    (('stiffness_model = "cai"', 'model = "lateral"\nstiffness_model = "cai"'),
     "dynamics.model: \"lateral\" integrates the lateral-torsional model: give [lateral]"),
])
def test_dynamics_bad_input_one_line_exit_2(tmp_path, capsys, edit, expect):
    from .conftest import assert_one_line_refusal

    assert_one_line_refusal("gears-planetary", edit, expect, tmp_path, capsys)
