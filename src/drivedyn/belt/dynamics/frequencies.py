"""What a run's verdict and its accuracy estimate read beside the time series: the samples judged,
the spans' flap frequencies (steady/flap.py) and the drive's modes (steady/modes.py) at the run's
speeds and tensions, in the summary (``flap``, ``modes``) and the dataset (``flap_frequency``, the
Campbell diagram's)."""
from __future__ import annotations

import numpy as np


def judged(ds):
    """Samples judged: the steady window, or for a run-up every sample in its bins."""
    t = ds["time"].values
    if "speed_bin" in ds.coords and "crank_rpm" in ds:
        c = ds["speed_bin"].values
        steps = np.diff(np.unique(c))            # a run-down's bins repeat the run-up's centres
        half = 0.5 * float(steps.min()) if len(steps) else 0.0
        return ds["crank_rpm"].values >= c.min() - half
    w = ds.attrs.get("steady_window")
    if w is None or len(np.atleast_1d(w)) != 2:
        return t >= t[0] + 0.75 * (t[-1] - t[0])
    return (t >= w[0]) & (t <= w[1])


def add_flap_and_modes(model, result) -> None:
    """summary["flap"] (span flap frequencies, belt/steady/flap.py), summary["modes"] (the rotational
    modes, belt/steady/modes.py) and ds["flap_frequency"] for the Campbell diagram."""
    from ...core.results import variable
    from ..steady import flap as flapmod
    from ..steady.modes import drive_modes

    s, ds = result.summary, result.ds
    if "flap" not in s:
        try:
            fl = flapmod.flap(model, ds, s)
        except Exception as exc:          # a layout that cannot be drawn: no flap, said so
            fl, s["flap_skipped"] = {}, str(exc)
        if fl:
            s["flap"] = fl
            spans = list(fl["spans"])
            f = np.array([[[fl["spans"][n][f"f{k + 1}"][b] for k in range(flapmod.MODES)] for n in spans]
                          for b in range(len(fl["speed_rpm"]))])
            # one update each: an assignment aligns the whole dataset again (2 ms apiece)
            ds.coords.update({"flap_rpm": variable(fl["speed_rpm"], ("flap_rpm",), "rpm", "crank speed of the flap point"),
                              "flap_span": spans, "flap_mode": list(range(1, flapmod.MODES + 1))})
            ds.update({"flap_frequency": variable(f, ("flap_rpm", "flap_span", "flap_mode"), "Hz",
                                                  "transverse (flap) natural frequency of the moving span")})
    if "modes" not in s:
        try:
            ten = None
            if "span_tension" in ds and ds.sizes.get("time", 0):
                ten = ds["span_tension"].values[judged(ds)].mean(axis=0)
                ten = ten if ten.size and np.all(np.isfinite(ten)) else None
            md = drive_modes(model, tensions=ten)     # at the run's mean span tensions
            s["modes"] = {"frequencies_hz": list(md.frequencies_hz)}
            if getattr(md, "free_rotor_hz", None):
                s["modes"]["free_rotor_hz"] = list(md.free_rotor_hz)
        except Exception:
            pass
