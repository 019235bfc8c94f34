"""A gearbox of stages in series: planetary stages, each driving the next one's input member through a
torsional shaft, the last one driving a gear train (parallel pairs), as wind-turbine and industrial
gearboxes are built.

The whole train's modes: the stage's model (torsional, planetary.matrices, or lateral-torsional,
planetary_lateral.matrices, the fixed member on its support) and the train's torsional model
(train.System.coupling, mean mesh stiffnesses) joined by the shaft, whose energy is
1/2 k (theta_out - theta_g)^2: theta_out the stage's output member (u / r in the lateral model),
theta_g the train gear on that shaft (its angle positive in its own direction of rotation, which
the shaft gives it from the output member). Each mode is attributed by its kinetic energy: the share
in the stage's coordinates. Successive stages are joined the same way, output member to input member.
"""
from __future__ import annotations

import math

import numpy as np

from . import stage as tors
from .lateral import MEMBERS


def stage_matrices(spec):
    """(M, K, names, g_in, g_out, model) of a stage with its fixed member held (or on its support
    stiffness); g_in, g_out are the rows with theta_input = g_in . q and theta_output = g_out . q."""
    lat = spec.lateral
    hold = lat.support_stiffness if lat is not None and lat.support_stiffness is not None else "fixed"
    st = tors.stage_of(spec, support={spec.fixed: hold})
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    if lat is None:
        M, K, names = tors.matrices(st)
        rows = []
        for member in (spec.input, output):
            g = np.zeros(len(names))
            g[names.index(member)] = 1.0
            rows.append(g)
        return M, K, names, rows[0], rows[1], "torsional"
    from . import lateral as pl

    ls = tors.lateral_stage(spec, st, {spec.fixed: hold})
    M, K, names = pl.matrices(ls)
    rows = []
    for member in (spec.input, output):
        g = np.zeros(len(names))
        g[names.index(f"{member}.u")] = 1.0 / ls.radius(member)
        rows.append(g)
    return M, K, names, rows[0], rows[1], "lateral-torsional"


def modes(model, sys_=None) -> dict:
    """Natural frequencies (Hz, rigid-body mode removed) of the planetary stages in series (each
    driving the next one's input member through its output shaft) and, with ``sys_``, the train the
    last one drives; each mode's kinetic-energy share in each stage."""
    from scipy.linalg import eigh

    chain = [model.planetary, *model.stages]
    blocks = [stage_matrices(st) for st in chain]
    sizes = [len(b[2]) for b in blocks]
    n_tr = sys_.n if sys_ is not None else 0
    N = sum(sizes) + n_tr
    M, K = np.zeros((N, N)), np.zeros((N, N))
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    coords = []
    for k, (Ms, Ks, names, g_in, g_out, kind) in enumerate(blocks):
        a, b = starts[k], starts[k + 1]
        M[a:b, a:b], K[a:b, a:b] = Ms, Ks
        coords += [f"{_label(k)}.{n}" for n in names]
    for k in range(len(chain) - 1):
        g = np.zeros(N)
        g[starts[k]:starts[k + 1]] = blocks[k][4]
        g[starts[k + 1]:starts[k + 2]] -= blocks[k + 1][3]
        K += chain[k].output_shaft_stiffness * np.outer(g, g)
    last = chain[-1]
    if sys_ is not None and last.output_gear is not None:
        Kt, _, Mt = sys_.coupling()
        s0 = starts[-1]
        M[s0:, s0:], K[s0:, s0:] = Mt, Kt
        g = np.zeros(N)
        g[starts[-2]:starts[-1]] = blocks[-1][4]
        g[s0 + sys_.names.index(last.output_gear)] = -1.0
        K += last.output_shaft_stiffness * np.outer(g, g)
        coords += list(sys_.names)
    w2, V = eigh(K, M)
    keep = w2 > 1e-9 * max(abs(w2).max(), 1.0)
    f = np.sqrt(w2[keep]) / (2 * math.pi)
    V = V[:, keep]
    ke = (M @ V) * V                                  # kinetic energy per coordinate and mode (mass-normalised: sums to 1)
    shares = {_label(k): [float(x) for x in ke[starts[k]:starts[k + 1]].sum(axis=0)] for k in range(len(chain))}
    return {"model": [b[5] for b in blocks], "stages": [_label(k) for k in range(len(chain))],
            "output_gear": last.output_gear, "natural_frequencies_hz": [float(x) for x in f],
            "stage_energy_share": [float(sum(v[r] for v in shares.values())) for r in range(len(f))],
            "energy_share": shares, "coordinates": coords}


def _label(k: int) -> str:
    """Summary name of stage ``k`` of a gearbox: "planetary", then "stage2", "stage3", ..."""
    return "planetary" if k == 0 else f"stage{k + 1}"


def output_torque(spec) -> float:
    """Torque (N m) the stage delivers at its output member: the input torque times the speed ratio
    input / output (no losses)."""
    st = tors.stage_of(spec)
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    return spec.torque * abs(tors._speed_ratio(st, spec.input, output))


def output_speed(spec) -> float:
    """Speed (rad/s) of the stage's output member with the rating's input speed."""
    st = tors.stage_of(spec)
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    return spec.rating.speed / abs(tors._speed_ratio(st, spec.input, output))


def add_stages(result, model, sys_=None, first=None, progress=None) -> None:
    """The summaries of a model's planetary stages (``planetary``, then ``stages.stage2``, ...), their
    diagnostics, their arrays for the plots (each stage's planet forces and modes, and its time
    integration's), and with more than one stage or a train driven, the gearbox's modes (gearbox.py;
    ``sys_`` the assembled train, if any). ``first``: stage 1's (summary, arrays), when already analysed."""
    summary, arrays = first if first is not None else analyse_stage(model.planetary, model.iso, "planetary", progress)
    result.summary["planetary"] = summary
    tors.diagnose_stage(result, summary, "planetary")
    stage_arrays(result, "planetary", arrays, loads=not result.ds.attrs.get("planetary_only"))
    if model.stages:
        result.summary["stages"] = {}
        for k, spec in enumerate(model.stages):
            s, a = analyse_stage(spec, model.iso, f"stages[{k}]", progress)
            result.summary["stages"][f"stage{k + 2}"] = s
            tors.diagnose_stage(result, s, f"stages.stage{k + 2}")
            stage_arrays(result, f"stage{k + 2}", a)
    last = [model.planetary, *model.stages][-1]
    if model.stages or (sys_ is not None and last.output_gear is not None):
        result.summary["gearbox"] = modes(model, sys_ if last.output_gear is not None else None)


def analyse_stage(spec, iso, where: str, progress=None) -> tuple[dict, dict]:
    """planetary.analyse of a stage in a run: with [dynamics], integrated in time first
    (planetary_dynamics.run), its K_v then in the summary and the rating."""
    dyn = None
    if spec.dynamics is not None:
        from .dynamics import run as integrate

        dyn = integrate(spec, where, progress)
    return tors.analyse(spec, iso, where, dynamics=dyn)


def stage_arrays(result, label: str, a: dict, loads: bool = True) -> None:
    """A stage's arrays into the Result's Dataset, named ``<label>_...`` (the plots read them): with
    ``loads`` its static planet forces and natural frequencies, and its time integration's mesh forces
    over the window and K_v sweep when it was integrated."""
    from ...core.results import variable

    ds = result.ds
    if loads:
        planet = f"{label}_planet"
        ds[f"{label}_sun_planet_force"] = variable(a["forces"]["sun_planet_force"], (planet,), "N",
                                                   "static sun-planet mesh force")
        ds[f"{label}_ring_planet_force"] = variable(a["forces"]["ring_planet_force"], (planet,), "N",
                                                    "static ring-planet mesh force")
        ds[f"{label}_natural_frequency"] = variable(a["f"], (f"{label}_mode",), "Hz",
                                                    "natural frequency of the stage (fixed member held)")
        if "lateral" in a:      # the load sharing the verdict reads (a floating sun's): the figure draws it
            la = a["lateral"]
            ds[f"{label}_lateral_sun_planet_force"] = variable(la["forces"]["sun_planet_force"], (planet,), "N",
                                                               "static sun-planet mesh force, lateral-torsional model")
            ds[f"{label}_lateral_ring_planet_force"] = variable(la["forces"]["ring_planet_force"], (planet,), "N",
                                                                "static ring-planet mesh force, lateral-torsional model")
        ds = ds.assign_coords({planet: np.arange(1, len(a["forces"]["share"]) + 1)})
    d = a.get("dynamics")
    if d is not None:
        mesh, time_ = f"{label}_mesh", f"{label}_dynamics_time"
        ds = ds.assign_coords({mesh: d["mesh_names"], time_: (time_, d["time"], {"units": "s", "long_name": "time in the window"})})
        ds[f"{label}_dynamics_force"] = variable(d["force"], (time_, mesh), "N",
                                                 "mesh force over the window at the operating speed (time integration)")
        ds[f"{label}_dynamics_force_quasi_static"] = variable(
            d["force_quasi_static"], (time_, mesh), "N",
            "quasi-static mesh force over the window (the static forces with the instant's mesh stiffnesses)")
        ds[f"{label}_dynamics_force_nominal"] = variable(d["force_nominal"], (mesh,), "N",
                                                         "static mesh force, mean stiffnesses")
        ds.attrs[f"{label}_dynamics_mesh_frequency_hz"] = float(d["mesh_frequency_hz"])
        ds.attrs[f"{label}_dynamics_speed"] = float(d["speed"])
        if "kv_sweep" in d:
            sp = f"{label}_sweep_speed"
            ds = ds.assign_coords({sp: (sp, d["sweep_speed"], {"units": "rad/s", "long_name": "input member speed"})})
            ds[f"{label}_kv_sweep"] = variable(d["kv_sweep"], (sp, mesh), "1", "K_v against the input member's speed")
    result.ds = ds


def run_stage(model, progress=None):
    """The Result of a model that is planetary stages alone (one, or several in series)."""
    import xarray as xr

    from ... import dumps
    from ...core.results import Result, unit_map, variable

    if progress:
        progress(0.0, "planetary stage")
    summary, a = analyse_stage(model.planetary, model.iso, "planetary", progress)
    ds = xr.Dataset(
        {"natural_frequency": variable(a["f"], ("mode",), "Hz", "natural frequency of the stage (fixed member held)"),
         "mode_shape": variable(a["V"], ("coordinate", "mode"), "1", "mass-normalised mode shape (rotations)"),
         "sun_planet_force": variable(a["forces"]["sun_planet_force"], ("planet",), "N", "static sun-planet mesh force"),
         "ring_planet_force": variable(a["forces"]["ring_planet_force"], ("planet",), "N", "static ring-planet mesh force"),
         "phase_sun_planet": variable(np.array(summary["phase_sun_planet"]), ("planet",), "1", "sun-planet mesh phase (periods)"),
         "phase_ring_planet": variable(np.array(summary["phase_ring_planet"]), ("planet",), "1", "ring-planet mesh phase (periods)")},
        coords={"mode": np.arange(len(a["f"])), "coordinate": a["names"], "planet": np.arange(1, len(summary["load_share"]) + 1)},
        attrs={"model_toml": dumps(model), "title": model.name or "planetary stage", "planetary_only": 1})
    if "lateral" in a:
        la = a["lateral"]
        ds["lateral_natural_frequency"] = variable(la["f"], ("lateral_mode",), "Hz",
                                                   "natural frequency of the lateral-torsional model")
        ds["lateral_sun_planet_force"] = variable(la["forces"]["sun_planet_force"], ("planet",), "N",
                                                  "static sun-planet mesh force, lateral-torsional model")
        ds["lateral_ring_planet_force"] = variable(la["forces"]["ring_planet_force"], ("planet",), "N",
                                                   "static ring-planet mesh force, lateral-torsional model")
    r = Result(kind="gear-train", ds=ds, summary={})
    add_stages(r, model, None, first=(summary, a), progress=progress)
    r.units = unit_map(r.summary, tors.PLANETARY_UNITS)
    if progress:
        progress(1.0, "done")
    return r
