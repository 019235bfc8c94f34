"""The span-stability model file (``kind = "span-stability"``): pure data, validated.

Tables (every quantity SI or a string with a unit):

    [span]         the free span: length (or a belt-drive model, or a belt-drive run's results.nc,
                   and a span name), mass per metre (or density and area), bending stiffness,
                   modal damping ratio
    [operation]    pretension F0 and belt speed V of the installation
    [excitation]   tooth-passing excitation: pulley teeth and radius (or pitch), period convention
    [tooth_force]  the tooth-force signal over one tooth: polynomial, samples, a time series (a CSV
                   file, or a belt-drive results.nc: the span's tension in its steady window), or a
                   given first-harmonic amplitude
    [chart]        the (F0, V) stability chart: ranges, points, tongues, Floquet, zoomed tongue
    [measurement]  optional: a measured span frequency -> tension (with uncertainties)
    [response]     optional: time response of the modal coordinate to the end-moment rate
"""
from __future__ import annotations

from typing import Literal, Optional

from pydantic import ValidationInfo, field_validator, model_validator

from ..core.model import Spec, quantity
from .criteria import Criteria

Force = quantity("N")
Speed = quantity("m/s")


def _relative_to_model(v, info: ValidationInfo):
    """A relative path that exists next to the model file is made absolute (else kept as given)."""
    from pathlib import Path

    base = (info.context or {}).get("base_dir")
    if v is None or base is None or Path(v).is_absolute():
        return v
    cand = Path(base) / v
    return str(cand.resolve()) if cand.exists() else v


def _check_range(v, what):
    if v is not None and not v[1] > v[0]:
        raise ValueError(f"must be [low, high] with high > low, got {list(v)}")
    if v is not None and v[0] < 0:
        raise ValueError(f"{what} must be >= 0, got {v[0]}")
    return v


def _check_points(v):
    if min(v) < 2 or max(v) > 2000:
        raise ValueError(f"each must lie in 2..2000, got {list(v)}")
    return v


class Span(Spec):
    """The free span, modelled as a simply supported moving beam (seed eq. 1-2)."""

    length: Optional[quantity("m", gt=0)] = None
    """Free length of the span between its tangent points (give this, belt_model or belt_results)."""
    belt_model: Optional[str] = None
    """A belt-drive model file (relative to this file, else the working folder, else a shipped example's name) and
    its span span_name: the length from its layout; mass per metre, bending stiffness and pretension default to its
    belt's."""
    belt_results: Optional[str] = None
    """A belt-drive run's results.nc (relative to this file): the span span_name from the model stored in it, and the
    pretension and speed default to the span's mean tension and belt speed in the run's steady window."""
    span_name: Optional[str] = None
    """Name of the span in the belt-drive model or results, "pulleyA-pulleyB" in belt order; needed with belt_model or
    belt_results."""
    mass_per_length: Optional[quantity("kg/m", gt=0)] = None
    """Mass of the belt per metre (or give density and area)."""
    density: Optional[quantity("kg/m^3", gt=0)] = None
    """Density of the belt material (with area, instead of mass_per_length)."""
    area: Optional[quantity("m^2", gt=0)] = None
    """Cross-section area of the belt (with density, instead of mass_per_length)."""
    bending_stiffness: Optional[quantity("N*m^2", ge=0)] = None
    """Bending stiffness EI of the belt (seed 002, eqs. 1-2: the span as a simply supported moving beam)."""
    damping_ratio: float = 0.0
    """Modal damping ratio zeta of the span's transverse modes (in [0, 1)); 0: undamped."""

    _belt_path = field_validator("belt_model", "belt_results")(classmethod(lambda cls, v, info: _relative_to_model(v, info)))

    @field_validator("damping_ratio")
    @classmethod
    def _zeta(cls, v):
        if not 0.0 <= v < 1.0:
            raise ValueError(f"must lie in [0, 1), got {v}")
        return v

    @model_validator(mode="after")
    def _sources(self):
        given = [k for k in ("length", "belt_model", "belt_results") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of span.length, span.belt_model or span.belt_results (with span.span_name)"
                             + (f" (got {', '.join(given)})" if given else ""))
        if self.length is None and not self.span_name:
            raise ValueError(f"span.{given[0]} needs span.span_name (e.g. \"driver-driven\")")
        if self.mass_per_length is not None and (self.density is not None or self.area is not None):
            raise ValueError("give span.mass_per_length or span.density with span.area, not both")
        if (self.density is None) != (self.area is None):
            raise ValueError("span.density and span.area go together")
        if self.length is not None:
            if self.mass_per_length is None and self.density is None:
                raise ValueError("span.mass_per_length (or span.density and span.area) is required")
            if self.bending_stiffness is None:
                raise ValueError("span.bending_stiffness is required")
        return self


class Operation(Spec):
    """The installation: static tension F0 and belt speed V."""

    pretension: Optional[quantity("N", gt=0)] = None
    """Static (installation) tension F0 of the span; none: from the belt-drive model or results."""
    speed: Optional[quantity("m/s", ge=0)] = None
    """Belt speed V; none: the belt results' span speed, else 0."""


class Excitation(Spec):
    """Tooth-passing excitation of the span tension."""

    teeth: int = 16
    """Number of teeth z of the pulley whose tooth passing excites the span (1..1000; 1: once per turn)."""
    pulley_radius: Optional[quantity("m", gt=0)] = None
    """Pitch radius r of that pulley (give this or pitch): tooth pitch 2 pi r / z."""
    pitch: Optional[quantity("m", gt=0)] = None
    """Tooth pitch p of the belt (give this or pulley_radius)."""
    period: Literal["tooth-passing", "seed"] = "tooth-passing"
    """Period convention of the tension fluctuation: "tooth-passing" (p / V, physical) or "seed" (the seed's printed T
    = pi r / (V z), half of it; seed 002)."""
    harmonics: int = 10
    """Number of Fourier harmonics of the tooth force kept (1..64)."""

    @field_validator("teeth")
    @classmethod
    def _z(cls, v):
        if v < 1:
            raise ValueError(f"must be >= 1, got {v}")
        if v > 1000:  # a toothed pulley has tens of teeth; 1 is the once-per-turn excitation
            raise ValueError(f"must be <= 1000, got {v}")
        return v

    @field_validator("harmonics")
    @classmethod
    def _h(cls, v):
        if not 1 <= v <= 64:
            raise ValueError(f"must lie in 1..64, got {v}")
        return v

    @model_validator(mode="after")
    def _geometry(self):
        if (self.pulley_radius is None) == (self.pitch is None):
            raise ValueError("give exactly one of excitation.pulley_radius or excitation.pitch")
        return self


class ToothForce(Spec):
    """The tooth force over one tooth (phase 0..2 pi), or its first-harmonic amplitude."""

    polynomial: Optional[list[float]] = None
    """Tooth force (N) over one tooth as polynomial coefficients in the phase phi (rad), highest power first (give
    exactly one of polynomial, samples, series, amplitude)."""
    samples: Optional[list[list[float]]] = None
    """Tooth force over one tooth as rows [phi (rad), force (N)], phi increasing over at most 2 pi (at least 4 rows)."""
    series: Optional[str] = None
    """A CSV file of time (s), force (N), relative to this file, or a belt-drive results.nc (the span's tension in its
    steady window)."""
    amplitude: Optional[quantity("N", ge=0)] = None
    """First-harmonic amplitude of the tooth force, given directly."""

    _series_path = field_validator("series")(classmethod(lambda cls, v, info: _relative_to_model(v, info)))

    @field_validator("polynomial")
    @classmethod
    def _poly(cls, v):
        if v is not None and len(v) < 1:
            raise ValueError("needs at least one coefficient")
        return v

    @field_validator("samples")
    @classmethod
    def _samples(cls, v):
        if v is None:
            return v
        if len(v) < 4 or any(len(r) != 2 for r in v):
            raise ValueError("needs at least 4 rows [phi (rad), force (N)]")
        phi = [r[0] for r in v]
        if any(b <= a for a, b in zip(phi, phi[1:])) or phi[-1] - phi[0] > 6.2832:
            raise ValueError("phi must increase strictly and span at most one tooth (2 pi)")
        return v

    @model_validator(mode="after")
    def _one(self):
        given = [k for k in ("polynomial", "samples", "series", "amplitude") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of tooth_force.polynomial, .samples, .series or .amplitude"
                             + (f" (got {', '.join(given)})" if given else ""))
        return self


class Zoom(Spec):
    """The zoomed principal tongue (seed fig. 3b); ranges default to around the tongue."""

    pretension: Optional[tuple[Force, Force]] = None
    """Pretension range [min, max] of the zoomed chart; none: around the principal tongue."""
    speed: Optional[tuple[Speed, Speed]] = None
    """Speed range [min, max] of the zoomed chart; none: around the principal tongue."""
    points: tuple[int, int] = (120, 120)
    """Grid points [pretension, speed] of the zoomed chart (2..2000 each)."""

    _pr = field_validator("pretension")(classmethod(lambda cls, v: _check_range(v, "pretension")))
    _sp = field_validator("speed")(classmethod(lambda cls, v: _check_range(v, "speed")))
    _pts = field_validator("points")(classmethod(lambda cls, v: _check_points(v)))


class Chart(Spec):
    """The stability chart in the (F0, V) plane (seed fig. 3a)."""

    pretension: tuple[Force, Force] = (0.0, 300.0)
    """Pretension range [min, max] of the stability chart (F0 axis)."""
    speed: tuple[Speed, Speed] = (0.0, 70.0)
    """Belt speed range [min, max] of the stability chart (V axis)."""
    points: tuple[int, int] = (200, 200)
    """Grid points [pretension, speed] of the chart (2..2000 each)."""
    tongues: int = 3
    """Number of parametric-resonance regions (tongues) computed, drawn and judged (1..8)."""
    floquet: bool = True
    """Compute the Floquet map over the chart's grid: the largest Floquet multiplier with the whole tooth-force
    signal, beside the tongues of its harmonics."""
    steps_per_oscillation: int = 48
    """Integration steps per excitation period of the Floquet computation (8..1000)."""
    zoom: Zoom = Zoom()
    """The zoomed principal tongue (seed 002, fig. 3b)."""

    _pr = field_validator("pretension")(classmethod(lambda cls, v: _check_range(v, "pretension")))
    _sp = field_validator("speed")(classmethod(lambda cls, v: _check_range(v, "speed")))

    _pts = field_validator("points")(classmethod(lambda cls, v: _check_points(v)))

    @field_validator("tongues")
    @classmethod
    def _tg(cls, v):
        if not 1 <= v <= 8:
            raise ValueError(f"must lie in 1..8, got {v}")
        return v

    @field_validator("steps_per_oscillation")
    @classmethod
    def _spo(cls, v):
        if not 8 <= v <= 1000:
            raise ValueError(f"must lie in 8..1000, got {v}")
        return v


class Measurement(Spec):
    """A measured span frequency, to be turned into the span tension (the field method)."""

    frequency: quantity("Hz", gt=0)
    """Measured transverse natural frequency of the span (for the tension, the field method)."""
    mode: int = 1
    """Mode number n of the measured frequency (1..10; 1: the fundamental)."""
    speed: quantity("m/s", ge=0) = 0.0
    """Belt speed during the measurement (0: at rest)."""
    frequency_uncertainty: quantity("Hz", ge=0) = 0.0
    """Uncertainty (+-) of the measured frequency."""
    length_uncertainty: quantity("m", ge=0) = 0.0
    """Uncertainty (+-) of the span length."""
    mass_uncertainty: quantity("kg/m", ge=0) = 0.0
    """Uncertainty (+-) of the mass per metre."""
    bending_uncertainty: quantity("N*m^2", ge=0) = 0.0
    """Uncertainty (+-) of the bending stiffness."""

    @field_validator("mode")
    @classmethod
    def _mode(cls, v):
        if not 1 <= v <= 10:
            raise ValueError(f"must lie in 1..10, got {v}")
        return v


class Response(Spec):
    """Time response of the modal coordinate q(t) (seed eq. 4) to M(t) = M0 + M1 Phi(t)."""

    duration: quantity("s", gt=0) = 0.5
    """Duration of the time response."""
    moment_amplitude: quantity("N*m", ge=0) = 0.0
    """Amplitude M1 of the end-moment fluctuation M(t) = M0 + M1 Phi(t) (seed 002, eq. 4)."""
    initial_displacement: quantity("m") = 1e-4
    """Initial modal displacement q(0) of the span."""
    points: int = 2000
    """Number of output points of the response (10..200000)."""

    @field_validator("points")
    @classmethod
    def _pts(cls, v):
        if not 10 <= v <= 200000:
            raise ValueError(f"must lie in 10..200000, got {v}")
        return v


class Model(Spec):
    """A belt span: its stability chart, frequencies and (optionally) tension from a frequency."""

    kind: Literal["span-stability"]
    """The kind of model file: "span-stability"."""
    schema_version: Literal[1] = 1
    """Version of the model-file format (1)."""
    name: str = ""
    """A name for the span, shown in reports."""
    span: Span
    """The free span: length (or its source), mass, bending stiffness, damping."""
    operation: Operation = Operation()
    """The installation's pretension and belt speed."""
    excitation: Excitation
    """What excites the span tension: the pulley's teeth (count, radius or pitch) and the period convention."""
    tooth_force: ToothForce
    """The tooth-force signal over one tooth, or its first-harmonic amplitude."""
    chart: Chart = Chart()
    """The (F0, V) stability chart (seed 002, fig. 3a)."""
    measurement: Optional[Measurement] = None
    """A measured span frequency turned into the span tension; none: not asked."""
    response: Optional[Response] = None
    """Time response of the span's modal coordinate; none: not computed."""
    criteria: Criteria = Criteria()
    """Design limits of the verdict (criteria.py, docs/criteria.md)."""

    @model_validator(mode="after")
    def _pretension(self):
        if self.span.length is not None and self.operation.pretension is None:
            raise ValueError("operation.pretension is required (or take it from span.belt_model or span.belt_results)")
        return self
