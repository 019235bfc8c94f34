"""``run`` for span-stability models: quantities, chart, bands, frequencies, measurement, response."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..core.errors import ModelError, SolverError
from ..core.model import dumps
from ..core.results import Result, unit_map, variable
from . import fourier
from ..mechanics.span.chart import UNSTABLE, bands, chart_variables, floquet_band, tongue_curves, zoom_ranges
from ..mechanics.span.frequencies import estimate_tension, span_frequencies
from ..mechanics.span.quantities import critical_speed, effective_tension, excitation_coefficient, excitation_frequency, natural_frequency
from .source import read_belt_run, resolve

KIND = "span-stability"

#: units of the summary keys (fnmatch patterns, first match wins; "1" for ratios)
UNITS = {
    "pretension": "N", "speed": "m/s", "v_critical": "m/s", "critical_speed_margin": "m/s", "euler_load": "N",
    "omega": "rad/s", "natural_frequency_hz": "Hz", "mu": "1", "effective_tension": "N",
    "excitation_frequency": "rad/s", "frequency_ratio": "1", "f1": "N", "tooth_force_mean": "N",
    "tooth_force_harmonics": "N", "pitch": "m", "span_length": "m", "mass_per_length": "kg/m",
    "bending_stiffness": "N*m^2", "damping_ratio": "1", "resonance_bands*": "m/s", "tongue_bands": "m/s",
    "floquet_multiplier": "1", "growth_rate": "1/s", "frequencies.*": "Hz",
    "measurement.frequency": "Hz", "measurement.speed": "m/s", "measurement.tension*": "N",
    "measurement.*_correction": "N", "measurement.uncertainty": "N", "measurement.contributions.*": "N",
    "response.*": "m", "belt_run.window": "s", "belt_run.tension_*": "N", "belt_run.speed": "m/s",
}


def tooth_force_harmonics(model, setup) -> fourier.Harmonics:
    """Harmonics of the model's tooth force (the series is analysed at the model's period)."""
    tf, n = model.tooth_force, model.excitation.harmonics
    if tf.polynomial is not None:
        return fourier.from_polynomial(tf.polynomial, n)
    if tf.samples is not None:
        s = np.asarray(tf.samples, dtype=float)
        return fourier.from_samples(s[:, 0], s[:, 1], n)
    if tf.series is not None:
        if setup.speed <= 0:
            raise ModelError("must be > 0 to analyse a time series at the tooth period", field="operation.speed")
        period = 2 * np.pi / float(excitation_frequency(setup.speed, setup.teeth, setup.pitch, setup.convention))
        return fourier.from_series(*series_of(model, setup), period, n)
    return fourier.Harmonics(0.0, np.array([tf.amplitude]), np.array([0.0]))


def series_of(model, setup):
    """(time, force) of ``tooth_force.series``: a CSV file, or a belt-drive results.nc whose span
    ``span.span_name`` gives its tension history in the run's steady window."""
    path = model.tooth_force.series
    if not str(path).lower().endswith(".nc"):
        return fourier.read_series(path)
    run = setup.belt_run
    if run is None or Path(run.path).resolve() != Path(path).resolve():
        if not model.span.span_name:
            raise ModelError("a belt-drive results file needs span.span_name (the span whose tension to take)",
                             field="tooth_force.series")
        run = read_belt_run(path, model.span.span_name, field="tooth_force.series")[2]
    return run.time, run.tension


def operating_point(setup, harm) -> dict:
    """Span quantities at the model's F0 and V (omega, mu None once the span has diverged)."""
    sp, F0, V = setup.span, setup.pretension, setup.speed
    vcr = float(critical_speed(F0, sp))
    w = float(excitation_frequency(V, setup.teeth, setup.pitch, setup.convention))
    diverged = V >= vcr
    Om = None if diverged else float(natural_frequency(F0, V, sp))
    return {
        "pretension": F0, "speed": V, "v_critical": vcr, "critical_speed_margin": vcr - V,
        "euler_load": sp.euler_load, "omega": Om,
        "natural_frequency_hz": None if diverged else Om / (2 * np.pi),
        "mu": None if diverged else float(excitation_coefficient(F0, V, harm.f1, sp)),
        "effective_tension": float(effective_tension(F0, V, sp)), "excitation_frequency": w,
        "frequency_ratio": w / Om if Om else None,
    }


def require_stable_speed(op, what: str):
    """ModelError naming operation.speed when ``what`` needs a frequency of a diverged span."""
    if op["omega"] is None:
        raise ModelError(f"{op['speed']:.4g} m/s is at or above the critical speed {op['v_critical']:.4g} m/s at "
                         f"pretension {op['pretension']:.4g} N: the span diverges and has no natural frequency "
                         f"({what} needs one)", field="operation.speed")


def run(model, progress=None) -> Result:
    """Run a span-stability model.

    Returns
    -------
    drivedyn.Result
        ``ds`` holds the chart on (pretension, speed), the zoomed tongue on
        (pretension_zoom, speed_zoom), tongue boundaries, frequency-vs-tension curves, the tooth
        force and its harmonics (and the modal response if asked); ``summary`` the headline numbers.
    """
    report = progress or (lambda f, t="": None)
    setup = resolve(model)
    harm = tooth_force_harmonics(model, setup)
    op = operating_point(setup, harm)
    if model.response is not None:
        require_stable_speed(op, "[response]")
    # a measurement no tension can explain is the user's mistake: refuse it before the chart
    measured = measurement_summary(model, setup) if model.measurement is not None else None
    sp, ch = setup.span, model.chart
    report(0.05, "chart")

    F0 = np.linspace(*ch.pretension, ch.points[0])
    V = np.linspace(*ch.speed, ch.points[1])
    data, coords = chart_variables(F0, V, setup, harm, ch.tongues, ch.floquet, ch.steps_per_oscillation)
    fine, fine_coords = tongue_curves(F0[-1], setup, harm, ch.tongues)
    data.update(fine)
    coords.update(fine_coords)
    report(0.5, "zoomed tongue")
    zp, zs = zoom_ranges(model, setup, harm)
    zd, zc = chart_variables(np.linspace(*zp, ch.zoom.points[0]), np.linspace(*zs, ch.zoom.points[1]),
                             setup, harm, 1, ch.floquet, ch.steps_per_oscillation, suffix="_zoom")
    data.update(zd)
    coords.update(zc)
    report(0.8, "bands and frequencies")

    exact, first = bands(setup, harm, ch.tongues)
    fl = floquet_band(setup.pretension, exact[0], setup, harm, ch.steps_per_oscillation) if exact[0] else None
    modes = np.arange(1, 4)
    freqs = None if op["omega"] is None else span_frequencies(setup.pretension, sp.mass_per_length, sp.length,
                                                               sp.bending_stiffness, setup.speed, 3)

    # frequency-vs-tension curves at the model's speed (NaN where the span diverges)
    curves = {k: np.full(len(F0), np.nan) for k in ("string", "beam", "moving_beam")}
    for i, T in enumerate(F0):
        if T > 0 and setup.speed < critical_speed(T, sp):
            f = span_frequencies(T, sp.mass_per_length, sp.length, sp.bending_stiffness, setup.speed, 1)
            for k in curves:
                curves[k][i] = f[k][0]
    for k, v in curves.items():
        data[f"frequency_{k}"] = variable(v, ("pretension",), "Hz", f"first span frequency ({k.replace('_', ' ')} model) at the model's speed")

    phase = np.linspace(0, 2 * np.pi, 361)
    data["tooth_force_series"] = variable(harm.evaluate(phase), ("phase",), "N", "tooth force, truncated Fourier series")
    if model.tooth_force.polynomial is not None:
        data["tooth_force"] = variable(np.polyval(model.tooth_force.polynomial, phase), ("phase",), "N", "tooth force (polynomial)")
    coords["phase"] = variable(phase, ("phase",), "rad", "phase over one tooth")
    kk = np.arange(1, len(harm.amplitudes) + 1)
    coords["harmonic"] = variable(kk, ("harmonic",), "1", "harmonic order of the tooth frequency")
    data["harmonic_amplitude"] = variable(harm.amplitudes, ("harmonic",), "N", "tooth force harmonic amplitude c_k")
    data["harmonic_phase"] = variable(harm.phases, ("harmonic",), "rad", "tooth force harmonic phase theta_k")

    summary = dict(op)
    summary.update({
        "f1": harm.f1, "tooth_force_mean": harm.mean, "tooth_force_harmonics": harm.amplitudes[:5].tolist(),
        "period_convention": setup.convention, "pitch": setup.pitch, "teeth": setup.teeth,
        "span_length": sp.length, "span_source": sp.source, "mass_per_length": sp.mass_per_length,
        "bending_stiffness": sp.bending_stiffness, "damping_ratio": sp.damping_ratio,
        "resonance_bands": [b for b in exact[:1] if b],
        "resonance_bands_first_order": [first] if first else [],
        "resonance_bands_floquet": [fl] if fl else [],
        "tongue_bands": exact,
        **point_floquet(setup, harm, ch.steps_per_oscillation),
        "in_resonance": bool(exact[0] and exact[0][0] <= setup.speed <= exact[0][1]),
        "frequencies": None if freqs is None else {k: np.asarray(v).tolist() for k, v in freqs.items()},
    })
    summary["stability"] = ("divergence" if op["omega"] is None else
                            "parametric resonance" if summary["floquet_multiplier"] > UNSTABLE else "stable")
    summary["stable"] = summary["stability"] == "stable"
    if model.measurement is not None:
        summary["measurement"] = measured
    if setup.belt_run is not None:   # where F0, V (and the tension history) came from, and how sound it was
        run_ = setup.belt_run
        summary["belt_run"] = {"file": run_.path, "span": run_.span_name, "status": run_.status,
                               "diagnostics": list(run_.diagnostics), "window": list(run_.window),
                               "tension_mean": float(run_.tension.mean()), "tension_min": float(run_.tension.min()),
                               "tension_max": float(run_.tension.max()), "speed": run_.speed}

    result_ds = xr.Dataset(data, coords=coords, attrs={"model_toml": dumps(model), "title": model.name or KIND})
    result_ds.coords["mode"] = variable(modes, ("mode",), "1", "mode number")
    result = Result(KIND, result_ds, summary)
    if op["omega"] is None:
        # the span model (a tensioned moving beam) needs N = F0 + F* - rhoA V^2 > 0: report, keep the chart
        result.diagnose("above-critical-speed",
                        f"the belt speed {op['speed']:.4g} m/s is at or above the critical speed V_cr = "
                        f"{op['v_critical']:.4g} m/s at pretension {op['pretension']:.4g} N: the span diverges (buckles) "
                        f"and the span model does not apply; only the chart is meaningful",
                        "speed", op["speed"], op["v_critical"], "m/s")
    elif summary["stability"] == "parametric resonance":
        # the chart shows it; the status must say it too (the report and the CLI list diagnostics)
        result.diagnose("parametric-resonance",
                        f"at {op['pretension']:.4g} N and {op['speed']:.4g} m/s the span is in a parametric-resonance "
                        f"region: largest Floquet multiplier {summary['floquet_multiplier']:.4g} per excitation period "
                        f"(growth rate {summary['growth_rate']:.3g} 1/s), so its transverse vibration grows; move the "
                        "pretension or speed out of the tongue or add damping",
                        "floquet_multiplier", summary["floquet_multiplier"], 1.0, "1")
    result.units = unit_map(summary, UNITS)
    if model.response is not None:
        report(0.9, "modal response")
        from .response import modal_response

        r = model.response
        try:
            t, q = modal_response(setup, harm, r.duration, r.moment_amplitude, r.initial_displacement, r.points)
        except SolverError as exc:
            result.success, result.message = False, str(exc)
            raise SolverError(str(exc), partial=result) from None
        result_ds["modal_coordinate"] = xr.DataArray(q, dims=("time",), attrs={"units": "m", "long_name": "modal coordinate q (mid-span deflection)"})
        result_ds.coords["time"] = variable(t, ("time",), "s", "time")
        tail = t >= 0.9 * t[-1]
        summary["response"] = {"max_deflection": float(np.max(np.abs(q))), "final_amplitude": float(np.max(np.abs(q[tail])))}
    result.units = unit_map(summary, UNITS)
    report(1.0, "done")
    return result


def point_floquet(setup, harm, steps) -> dict:
    """Largest Floquet multiplier and growth rate ln|lambda| / T (1/s) at the model's F0 and V."""
    from ..mechanics.span.floquet import hill_parameters, multipliers

    if setup.speed <= 0:
        return {"floquet_multiplier": 1.0, "growth_rate": 0.0}
    al, be, ga = hill_parameters(setup.pretension, setup.speed, setup.span, harm.f1, setup.teeth, setup.pitch,
                                 setup.convention)
    rho = float(multipliers(al, be, ga, *harm.shape(), steps)[2])
    period = 2 * np.pi / float(excitation_frequency(setup.speed, setup.teeth, setup.pitch, setup.convention))
    return {"floquet_multiplier": rho, "growth_rate": float(np.log(rho) / period)}


def measurement_summary(model, setup) -> dict:
    """Tension from the measured frequency, with corrections and uncertainty (summary block)."""
    me, sp = model.measurement, setup.span
    try:
        e = estimate_tension(me.frequency, sp.mass_per_length, sp.length, sp.bending_stiffness, me.speed, me.mode,
                             me.frequency_uncertainty, me.length_uncertainty, me.mass_uncertainty, me.bending_uncertainty)
    except ModelError as exc:
        raise ModelError(str(exc).split(": ", 1)[-1], field=f"measurement.{exc.field or 'frequency'}") from None
    return {"frequency": me.frequency, "mode": me.mode, "speed": me.speed, "tension": e.tension,
            "tension_string": e.tension_string, "bending_correction": e.bending_correction,
            "speed_correction": e.speed_correction, "uncertainty": e.uncertainty, "contributions": e.contributions}
