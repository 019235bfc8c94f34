"""The gear-train model file (``kind = "gear-train"``): pure data, validated.

A gear train is a set of spur gears (rigid bodies turning about fixed axes), meshes between pairs
of them (spring-damper along the line of action with a time-varying stiffness), torsional shafts
joining gears on one axis, and external torques. Sign convention (seed 003, eq. 9-11): every gear's
angle and speed are positive in its own nominal direction of rotation; a torque is positive when it
drives the gear in that direction (loads are negative).
"""
from __future__ import annotations

from typing import Literal, Optional

from pydantic import Field, field_validator, model_validator

from ..core.model import Spec, check_name, quantity, table_rows
from .criteria import Criteria

#: highest pitch-line speed accepted (m/s): turbo gears, the fastest in service, stay below 200 m/s
V_MAX = 300.0

Length = quantity("m")
Time = quantity("s")
Stress = quantity("Pa", gt=0)
Steel = Literal["case-carburized", "through-hardened"]


def _name(v):
    return check_name(v)


def _table(value, units, field):
    return table_rows(value, units, field, min_rows=2)


def _engagement(v):
    """A tooth pair's stiffness ramp, in mesh periods: [0, 0.45] (Stiffness and PlanetaryDynamics)."""
    if not 0.0 <= v <= 0.45:
        raise ValueError(f"must lie in [0, 0.45] mesh periods, got {v}")
    return v


def _unit_interval(v):
    """A ratio in [0, 1) (none passes)."""
    if v is not None and not 0.0 <= v < 1.0:
        raise ValueError(f"must lie in [0, 1), got {v}")
    return v


def _sweep_ranges(spec):
    """A K_v sweep's counts and speeds in range (Sweep and PlanetaryDynamics): each count is one
    settle + window run, cycles x steps set its length."""
    if not 2 <= spec.count <= 10_000:
        raise ValueError(f"count must lie in 2..10000, got {spec.count}")
    if not (2 <= spec.window_cycles <= 10_000 and 16 <= spec.steps_per_cycle <= 10_000):
        raise ValueError("window_cycles must lie in 2..10000 and steps_per_cycle in 16..10000")
    if spec.speed_min is not None and spec.speed_max is not None and not spec.speed_max > spec.speed_min:
        raise ValueError("speed_max must be > speed_min")
    return spec


class Gear(Spec):
    """A spur or helical gear: tooth data (basic rack in modules, normal section), blank and external torque."""

    name: str
    """Name of the gear, used by meshes, shafts and the drive; no spaces, dots or slashes."""
    teeth: int
    """Number of teeth z (5..2000)."""
    module: quantity("m", gt=0)
    """Normal module m_n of the basic rack (ISO 54; the transverse module is m_n / cos beta)."""
    pressure_angle: quantity("rad", gt=0, lt=0.8) = 0.3490658503988659
    """Normal pressure angle alpha_n of the basic rack (20 deg: ISO 53)."""
    helix_angle: quantity("rad", ge=0, lt=0.7853981633974483) = 0.0
    """Helix angle beta at the reference diameter (0: spur; helical gears run at 8-30 deg, double helical up to 40;
    below 45 deg, the limit of the model's thin slices)."""
    hand: Literal["right", "left"] = "right"
    """Hand of the helix; meshing external helical gears have opposite hands."""
    profile_shift: float = 0.0
    """Profile shift coefficient x, in modules (ISO 21771; positive away from the gear's centre)."""
    face_width: quantity("m", gt=0)
    """Face width b of the teeth, along the axis."""
    inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of the gear (and what turns rigidly with it) about its axis."""
    tip_diameter: Optional[quantity("m", gt=0)] = None
    """Tip diameter d_a; none: from the basic rack and profile shift, d + 2 m_n (h_aP/m + x) (ISO 21771)."""
    addendum: float = 1.0
    """Addendum h_aP / m of the basic rack (1: ISO 53)."""
    dedendum: float = 1.25
    """Dedendum h_fP / m of the basic rack (1.25: ISO 53)."""
    bore_diameter: Optional[quantity("m", gt=0)] = None
    """Inner diameter of the gear body, for the fillet-foundation term of the potential-energy stiffness; none: the
    root circle."""
    youngs_modulus: quantity("Pa", gt=0) = 206e9
    """Young's modulus of the gear's material (206 GPa: steel, ISO 6336-1)."""
    poisson: float = 0.3
    """Poisson's ratio of the gear's material (0.3: steel)."""
    torque: quantity("N*m") = 0.0
    """Constant external torque on the gear, positive when it drives the gear in its nominal direction of rotation
    (loads are negative; seed 003, eqs. 9-11)."""
    torque_speed: Optional[list[list]] = None
    """Torque over the gear's speed as rows [speed, torque] (at least 2), added to torque; same sign convention."""
    torque_time: Optional[list[list]] = None
    """Torque over time as rows [time, torque] (at least 2), added to torque; same sign convention."""
    load_fraction: float = 0.0
    """Share of the input power taken off at this gear as a load (0..1; the shares add up to at most 1), lowered by
    the mean tooth-friction loss so that the train keeps its speed."""
    root_radius: float = 0.25
    """Root radius rho_fP / m of the basic rack (the tool's tip radius; ISO 53 and DIN 867 racks have 0.2..0.4), for
    the ISO 6336-3 tooth root (in (0, 0.6])."""
    steel: Optional[Literal["case-carburized", "through-hardened"]] = None
    """This gear's material for the rating, from the table of rating.py (ISO 6336 class and allowable stresses); none:
    iso's."""
    flank_roughness: Optional[quantity("m", gt=0)] = None
    """This gear's flank roughness R_z (ISO 6336-2 Z_R); none: iso's."""
    root_roughness: Optional[quantity("m", gt=0)] = None
    """This gear's root roughness R_z (ISO 6336-3 Y_RrelT); none: iso's."""
    yield_strength: quantity("Pa", gt=0) | None = None
    """This gear's yield strength R_p0.2, for the relative notch sensitivity Y_deltarelT of a through-hardened gear
    (ISO 6336-3); none: its steel's, else iso's."""

    @field_validator("name")
    @classmethod
    def _n(cls, v):
        return _name(v)

    @field_validator("root_radius")
    @classmethod
    def _rho(cls, v):
        # ISO 53 and DIN 867 racks have 0.2..0.4 m; 0 is a sharp tool, above 0.6 the fillet meets the flank
        if not 0.0 < v <= 0.6:
            raise ValueError(f"must lie in (0, 0.6] modules, got {v}")
        return v

    @field_validator("teeth")
    @classmethod
    def _z(cls, v):
        if v < 5:
            raise ValueError(f"must be >= 5 (an involute gear needs at least 5 teeth), got {v}")
        if v > 2000:  # the largest cut spur gears have a few hundred teeth; the mesh tables scale with z
            raise ValueError(f"must be <= 2000, got {v}")
        return v

    @field_validator("profile_shift")
    @classmethod
    def _x(cls, v):
        # ISO 21771 practice lies within -1..+1.5; beyond +-3 the tooth is pointed or fully undercut
        if not -3.0 < v < 3.0:
            raise ValueError(f"must lie in (-3, 3) modules, got {v}")
        return v

    @field_validator("poisson")
    @classmethod
    def _nu(cls, v):
        if not 0.0 <= v < 0.5:
            raise ValueError(f"must lie in [0, 0.5), got {v}")
        return v

    @field_validator("addendum", "dedendum")
    @classmethod
    def _rack(cls, v):
        if not 0.0 < v < 3.0:
            raise ValueError(f"must lie in (0, 3) modules, got {v}")
        return v

    @field_validator("load_fraction")
    @classmethod
    def _lf(cls, v):
        if not 0.0 <= v <= 1.0:
            raise ValueError(f"must lie in [0, 1], got {v}")
        return v

    @field_validator("torque_speed")
    @classmethod
    def _ts(cls, v):
        return None if v is None else _table(v, ("rad/s", "N*m"), "torque_speed")

    @field_validator("torque_time")
    @classmethod
    def _tt(cls, v):
        return None if v is None else _table(v, ("s", "N*m"), "torque_time")


class Stiffness(Spec):
    """Time-varying mesh stiffness: its shape and where its magnitude comes from.

    ``model``: ``cai`` (Cai's parabola per tooth pair, normalised by the mean mesh stiffness),
    ``rectangular`` (single/double-contact wave), ``potential-energy`` (from the tooth geometry),
    ``constant`` (the mean only). The magnitude of cai/rectangular/constant is ``mean`` if given,
    else ISO 6336-1 c_gamma_alpha * b; a rectangular wave may instead give ``single`` and ``double``.
    """

    model: Literal["cai", "rectangular", "potential-energy", "constant"] = "cai"
    """Shape of the time-varying mesh stiffness: "cai" (Cai's parabola per tooth pair), "rectangular"
    (single/double-contact wave), "potential-energy" (from the tooth geometry), "constant" (the mean only)."""
    mean: Optional[quantity("N/m", gt=0)] = None
    """Mean mesh stiffness along the line of action; none: ISO 6336-1 c_gamma_alpha x b (method B)."""
    single: Optional[quantity("N/m", gt=0)] = None
    """Stiffness in single-tooth contact of the rectangular wave (give with double; not with mean)."""
    double: Optional[quantity("N/m", gt=0)] = None
    """Stiffness in double-tooth contact of the rectangular wave (give with single; not with mean)."""
    engagement: float = 0.0
    """Duration, in mesh periods, over which a tooth pair's stiffness ramps in and out (smoothstep; 0: a step; at most
    0.45)."""

    _eng = field_validator("engagement")(classmethod(lambda cls, v: _engagement(v)))

    @model_validator(mode="after")
    def _given(self):
        if (self.single is None) != (self.double is None):
            raise ValueError("give both single and double (N/m), or neither")
        if self.single is not None and self.model != "rectangular":
            raise ValueError(f"single/double are values of the rectangular wave, not of model {self.model!r}")
        if self.single is not None and self.mean is not None:
            raise ValueError("give either mean or single/double, not both")
        if self.model == "potential-energy" and self.mean is not None:
            raise ValueError("the potential-energy stiffness is computed from the teeth; remove mean")
        return self


class Mesh(Spec):
    """A mesh between two external spur gears: ``gears = [driving, driven]``."""

    name: str
    """Name of the mesh, used in results; no spaces, dots or slashes."""
    gears: tuple[str, str]
    """The two gears in mesh, [driving, driven] (external spur or helical gears)."""
    stiffness: Stiffness = Stiffness()
    """The mesh's time-varying stiffness."""
    damping: Optional[quantity("N*s/m", ge=0)] = None
    """Viscous mesh damping along the line of action; give this or damping_ratio, not both."""
    damping_ratio: Optional[float] = None
    """Mesh damping as a ratio of the critical damping of the pair's reduced mass on the mean stiffness (in [0, 1));
    none, with no damping either: 0.05."""
    friction: float = 0.0
    """Tooth friction coefficient mu (in [0, 1); 0: no friction)."""
    position_angle: quantity("rad") = 0.0
    """Angular position of the mesh around the driving gear; sets the mesh's phase when phase is not given (-z_driving
    x angle / 2 pi, mesh periods)."""
    phase: Optional[float] = None
    """Phase of the mesh's stiffness cycle, in mesh periods (in [0, 1)); none: from position_angle."""
    center_distance: Optional[quantity("m", gt=0)] = None
    """Working centre distance; none: the zero-backlash one of the two gears' profile shifts (ISO 21771)."""
    separation: bool = False
    """Let the teeth separate: the mesh force cannot pull, and the teeth cross the backlash before they touch again;
    false: a linear mesh whose force may go negative."""
    backlash: quantity("m", ge=0) = 0.0
    """Circumferential backlash along the line of action (used with separation)."""

    @field_validator("name")
    @classmethod
    def _n(cls, v):
        return _name(v)

    _unit = field_validator("friction", "damping_ratio")(classmethod(lambda cls, v: _unit_interval(v)))

    @field_validator("phase")
    @classmethod
    def _phase(cls, v):
        if v is not None and not 0.0 <= v < 1.0:
            raise ValueError(f"must lie in [0, 1) mesh periods, got {v}")
        return v

    @model_validator(mode="after")
    def _checks(self):
        if self.gears[0] == self.gears[1]:
            raise ValueError(f"gears: a mesh needs two different gears, got {list(self.gears)}")
        if self.damping is not None and self.damping_ratio is not None:
            raise ValueError("give damping (N s/m) or damping_ratio, not both")
        return self


class Shaft(Spec):
    """A torsional shaft joining two gears on the same axis (they turn the same way)."""

    name: str
    """Name of the shaft, used in results; no spaces, dots or slashes."""
    gears: tuple[str, str]
    """The two gears the shaft joins (on one axis, turning the same way)."""
    stiffness: quantity("N*m/rad", gt=0)
    """Torsional stiffness of the shaft between the two gears."""
    damping: quantity("N*m*s/rad", ge=0) = 0.0
    """Torsional damping of the shaft."""

    @field_validator("name")
    @classmethod
    def _n(cls, v):
        return _name(v)


class Drive(Spec):
    """Operating point: the input gear, its nominal speed and the input power or torque."""

    input: str
    """Name of the input (driving) gear."""
    speed: quantity("rad/s", gt=0)
    """Nominal speed of the input gear, in its nominal direction of rotation."""
    power: Optional[quantity("W", gt=0)] = None
    """Input power (give this or torque)."""
    torque: Optional[quantity("N*m", gt=0)] = None
    """Input torque on the input gear (give this or power)."""

    @model_validator(mode="after")
    def _load(self):
        if (self.power is None) == (self.torque is None):
            raise ValueError("give exactly one of drive.power (W) or drive.torque (N m)")
        return self


class Simulation(Spec):
    """Time integration: the seed's fixed-step RK4 or adaptive Dormand-Prince 5(4)."""

    method: Literal["rk4", "dopri5"] = "rk4"
    """Time integration: "rk4" (the seed's fixed-step fourth-order Runge-Kutta, seed 003) or "dopri5" (adaptive
    Dormand-Prince 5(4))."""
    step: quantity("s", gt=0) = 5e-6
    """Time step of rk4 (the first step of dopri5)."""
    duration: quantity("s", gt=0) = 0.05
    """Simulated time."""
    start: Literal["static", "ramp", "rest"] = "static"
    """Initial state: "static" (static equilibrium at the start position, no start-up step), "ramp" (the load ramped
    smoothly over ramp_time), "rest" (undeflected, full load at t = 0: a start-up transient)."""
    ramp_time: quantity("s", ge=0) = 0.0
    """Duration of the load ramp of start = "ramp"."""
    steady_window: Optional[tuple[Time, Time]] = None
    """Time window [start, end] in which K_v and the steady results are read; none: the last quarter of the run."""
    output_interval: Optional[quantity("s", gt=0)] = None
    """Sampling interval of the written time series; none: every step (rk4) or duration / 20000 (dopri5)."""
    rtol: float = 1e-8
    """Relative error tolerance of dopri5 (rk4 ignores it)."""
    atol: quantity("m", gt=0) = 1e-12
    """Absolute error tolerance of dopri5 on the deflections (rk4 ignores it)."""

    @model_validator(mode="after")
    def _window(self):
        w = self.steady_window
        if w is not None and not (0 <= w[0] < w[1] <= self.duration * (1 + 1e-9)):
            raise ValueError(f"steady_window must be [start, end] with 0 <= start < end <= duration, got {list(w)}")
        if self.start == "ramp" and self.ramp_time <= 0:
            raise ValueError("start = 'ramp' needs ramp_time > 0")
        if self.step > self.duration:
            raise ValueError("step is longer than duration")
        from ..core.limits import bytes_problem, steps_problem

        if self.method == "rk4":
            problem = steps_problem(self.duration / self.step, "step", "a longer step or a shorter duration")
            if problem:
                raise ValueError(problem)
        # samples: every step (rk4) or duration/20000 (dopri5) unless output_interval is given;
        # about 100 doubles a sample for a train of a few gears, three copies on the way to the file
        interval = self.output_interval or (self.step if self.method == "rk4" else self.duration / 20000)
        samples = self.duration / interval
        problem = bytes_problem(3 * 800 * samples, "output_interval",
                                f"{samples:.3g} samples: a longer output_interval or a shorter duration")
        if problem:
            raise ValueError(problem)
        return self


class Sweep(Spec):
    """K_v against input speed at the nominal torques (a run per speed, in compiled code)."""

    enabled: bool = False
    """Run the speed sweep: K_v against input speed at the nominal torques."""
    speed_min: Optional[quantity("rad/s", gt=0)] = None
    """Lowest input speed of the sweep; none: speed_max / 100."""
    speed_max: Optional[quantity("rad/s", gt=0)] = None
    """Highest input speed of the sweep; none: 1.3 x the speed where the first mesh frequency meets the highest
    natural frequency."""
    count: int = 200
    """Number of speeds of the sweep (2..10000)."""
    settle: Optional[quantity("s", gt=0)] = None
    """Settling time before K_v is read at each speed; none: five decay times of the least damped mode, at most 0.5 s."""
    window_cycles: int = 20
    """Mesh periods of the first mesh over which K_v is read at each speed (2..10000)."""
    steps_per_cycle: int = 64
    """RK4 steps per mesh period at least (16..10000)."""

    _range = model_validator(mode="after")(lambda self: _sweep_ranges(self))


class Iso(Spec):
    """ISO 6336-1:2006 inputs for c', c_gamma and the method B dynamic factor, and the ISO 6336-2/-3
    rating (method B) of every mesh: material, lubricant, roughness, life and minimum safety factors."""

    application_factor: float = 1.0
    """Application factor K_A (ISO 6336-1, 6.2 / annex B: 1 for uniform driver and load; in [1, 10])."""
    low_load: bool = True
    """Apply the low-load factor to c' below K_A F_t / b = 100 N/mm (ISO 6336-1:2006, 9.3.1)."""
    blank_factor: float = 1.0
    """Gear blank factor C_R of c' (ISO 6336-1:2006, 9.3.4: 1 for solid blanks)."""
    pitch_deviation: quantity("m", ge=0) = 7e-6
    """Transverse base pitch deviation f_pb (ISO 6336-1 method B dynamic factor)."""
    profile_deviation: quantity("m", ge=0) = 7e-6
    """Profile form deviation f_f_alpha (ISO 6336-1 method B dynamic factor)."""
    material: Literal["St", "V", "Eh", "NT", "GG"] = "Eh"
    """ISO 6336 material class: St (structural steel), V (through-hardened), Eh (case-hardened), NT (nitrided), GG
    (grey cast iron); sets the running-in allowances of ISO 6336-1."""
    sigma_hlim: quantity("Pa", gt=0) = 1500e6
    """Allowable contact stress number sigma_Hlim (ISO 6336-5)."""
    tip_relief: Optional[quantity("m", ge=0)] = None
    """Tip relief C_a (ISO 6336-1 method B); none: no tip relief."""
    rating: bool = True
    """Rate every mesh to ISO 6336-2/-3 (method B) with the run's K_v."""
    steel: Optional[Literal["case-carburized", "through-hardened"]] = None
    """A steel from the table of rating.py (sets material, sigma_hlim, sigma_flim and yield_strength; give it or
    them); none: the fields as given."""
    sigma_flim: quantity("Pa", gt=0) = 430e6
    """Allowable bending stress number sigma_Flim (ISO 6336-5)."""
    yield_strength: Optional[quantity("Pa", gt=0)] = None
    """Yield strength R_p0.2 of a through-hardened steel, for the relative notch sensitivity Y_deltarelT (ISO 6336-3);
    none: Y_deltarelT = 1."""
    life: quantity("s", gt=0) = 20000 * 3600.0
    """Required life of the gears, for the life factors Z_NT and Y_NT (20 000 h)."""
    lubricant_viscosity: quantity("m^2/s", gt=0) = 220e-6
    """Kinematic viscosity of the lubricant at 40 deg C (ISO VG grade; ISO 6336-2 Z_L, Z_v)."""
    flank_roughness: quantity("m", gt=0) = 6e-6
    """Flank roughness R_z (ISO 6336-2 Z_R)."""
    root_roughness: quantity("m", gt=0) = 10e-6
    """Root roughness R_z (ISO 6336-3 Y_RrelT)."""
    mesh_misalignment: quantity("m", ge=0) = 10e-6
    """Mesh misalignment f_ma, for the face load factor K_Hbeta (ISO 6336-1)."""
    face_load_factor: Optional[float] = None
    """Face load factor K_Hbeta given (in [1, 10]); none: computed (ISO 6336-1)."""
    transverse_load_factor: Optional[float] = None
    """Transverse load factor K_Halpha given (in [1, 10]); none: computed (ISO 6336-1)."""
    dynamic_factor: Optional[float] = None
    """Dynamic factor K_v given for the rating (in [1, 10]), instead of the run's and method B's."""
    min_safety_pitting: float = Field(1.0, json_schema_extra={"minimum": 1.0})
    """Minimum safety factor against pitting S_Hmin the verdict requires (ISO 6336-2)."""
    min_safety_bending: float = Field(1.0, json_schema_extra={"minimum": 1.0})
    """Minimum safety factor against tooth-root bending S_Fmin the verdict requires (ISO 6336-3)."""

    @field_validator("blank_factor")
    @classmethod
    def _pos(cls, v):
        if not v > 0:
            raise ValueError(f"must be > 0, got {v}")
        return v

    @field_validator("min_safety_pitting", "min_safety_bending")
    @classmethod
    def _safety(cls, v):
        # ISO 6336-2/-3: the permissible stress is the limit over S_min; a minimum below 1 permits
        # more than the material's endurance limit and passes a flank or root the rating says fails
        if not v >= 1.0:
            raise ValueError(f"must be >= 1 (below 1 it passes a flank or root past its endurance limit), got {v}")
        return v

    @field_validator("application_factor")
    @classmethod
    def _ka(cls, v):
        # ISO 6336-1, 6.2 / annex B: K_A >= 1 (1 for uniform driver and load); below it the rating
        # would credit the drive with less load than its nominal torque
        if not 1.0 <= v <= 10.0:
            raise ValueError(f"must lie in [1, 10] (ISO 6336-1: K_A >= 1), got {v}")
        return v

    @field_validator("face_load_factor", "transverse_load_factor", "dynamic_factor")
    @classmethod
    def _factor(cls, v):
        # ISO 6336-1 load factors are >= 1; above 10 the load distribution model has no meaning
        if v is not None and not 1.0 <= v <= 10.0:
            raise ValueError(f"must lie in [1, 10], got {v}")
        return v

    @field_validator("life")
    @classmethod
    def _life(cls, v):
        if v > 1e6 * 3600:   # a million hours (114 years) is beyond any design life
            raise ValueError(f"must be <= 1e6 h, got {v / 3600:.4g} h")
        return v

    @field_validator("lubricant_viscosity")
    @classmethod
    def _nu40(cls, v):
        # ISO 3448 grades run from VG 2 to VG 3200 (mm^2/s at 40 deg C)
        if not 2e-6 <= v <= 3200e-6:
            raise ValueError(f"must lie in 2..3200 mm^2/s (ISO VG 2..3200), got {v * 1e6:.4g} mm^2/s")
        return v

    @model_validator(mode="after")
    def _steel(self):
        # a steel from the table sets these four; a value away from its default says the user meant another
        # (compared with the defaults, not with the fields set, so that a dumped model loads back)
        given = sorted(k for k in ("sigma_hlim", "sigma_flim", "material", "yield_strength")
                       if getattr(self, k) != type(self).model_fields[k].default)
        if self.steel is not None and given:
            raise ValueError(f"give steel or {', '.join(given)}, not both")
        return self


class PlanetaryLateral(Spec):
    """The lateral-torsional model of the stage (Lin & Parker, J. Vib. Acoust. 121 (1999) 316-321):
    masses and radial bearings of sun, ring and carrier, the planets' pin bearings, and the torsional
    support of the held member."""

    sun_mass: quantity("kg", gt=0)
    """Mass of the sun (with what moves rigidly with it) for the lateral model (Lin & Parker 1999)."""
    ring_mass: quantity("kg", gt=0)
    """Mass of the ring for the lateral model."""
    carrier_mass: quantity("kg", gt=0)
    """Mass of the carrier for the lateral model."""
    planet_bearing_stiffness: quantity("N/m", gt=0)
    """Stiffness of each planet's pin bearing, radial and tangential."""
    sun_bearing_stiffness: quantity("N/m", ge=0) = 0.0
    """Radial bearing stiffness of the sun; 0: a floating sun, centred by its meshes."""
    ring_bearing_stiffness: Optional[quantity("N/m", gt=0)] = None
    """Radial bearing stiffness of the ring; none: held rigidly in translation."""
    carrier_bearing_stiffness: Optional[quantity("N/m", gt=0)] = None
    """Radial bearing stiffness of the carrier; none: held rigidly in translation."""
    support_stiffness: Optional[quantity("N*m/rad", gt=0)] = None
    """Torsional stiffness of the held member's support; none: rigid."""


class PlanetaryRating(Spec):
    """ISO 6336-2/-3 rating of the sun-planet and ring-planet meshes (the rest of the data from [iso])."""

    face_width: quantity("m", gt=0)
    """Face width of the sun-planet and ring-planet meshes."""
    speed: quantity("rad/s", gt=0)
    """Speed of the input member, for the rating."""
    load_sharing_factor: Optional[float] = None
    """Mesh load factor K_gamma (in [1, 3]); none: from the computed load sharing."""
    dynamic_factors: Optional[tuple[float, float]] = None
    """K_v of the sun-planet and ring-planet meshes; none: ISO 6336-1 method B."""
    face_load_factors: Optional[tuple[float, float]] = None
    """K_Hbeta of the sun-planet and ring-planet meshes; none: iso's."""
    steels: Optional[tuple[Steel, Steel, Steel]] = None
    """Steels of sun, planet and ring from the table of rating.py; none: iso's for all."""
    ring_hardness: Optional[float] = None
    """Brinell hardness (HB) of a through-hardened ring, for the work-hardening factor Z_W (ISO 6336-2)."""
    sigma_hlim: Optional[tuple[Stress, Stress, Stress]] = None
    """sigma_Hlim of sun, planet and ring; none: the steels' (or iso's)."""
    sigma_flim: Optional[tuple[Stress, Stress, Stress]] = None
    """sigma_Flim of sun, planet and ring; none: the steels' (or iso's)."""
    tip_diameters: Optional[tuple[Length, Length, Length]] = None
    """Tip diameters of sun, planet and ring (the ring's inner); none: ISO 21771."""
    bore_diameters: tuple[Length, Length, Length] = (0.0, 0.0, 0.0)
    """Bore diameters of sun and planet and the ring's outer diameter, for the reduced masses (0: solid)."""
    flank_roughness: Optional[tuple[Length, Length, Length]] = None
    """Flank roughness R_z of sun, planet and ring; none: iso's."""
    root_roughness: Optional[tuple[Length, Length, Length]] = None
    """Root roughness R_z of sun, planet and ring; none: iso's."""
    root_radius: tuple[float, float, float] = (0.25, 0.25, 0.25)
    """Root radii rho_fP / m of the racks of sun, planet and ring."""
    yield_strength: dict[Literal["sun", "planet", "ring"], Stress] = Field(default_factory=dict)
    """Yield strength R_p0.2 per gear (keys sun, planet, ring), for the relative notch sensitivity Y_deltarelT of
    a through-hardened gear (ISO 6336-3); a gear not named: its steel's, else iso's."""
    ring_root_section: tuple[Length, Length, Length] | None = None
    """The ring's root section at its 60 deg tangent (ISO 6336-3, internal gears), from its tooth form: chord s_Fn,
    fillet radius rho_F, diameter d_sFn; none: the ring's root is not rated."""

    @field_validator("ring_root_section")
    @classmethod
    def _section(cls, v):
        if v is not None and not (all(x > 0 for x in v) and v[0] < v[2] and v[1] < v[2]):
            got = ", ".join(f"{x:.6g} m" for x in v)
            raise ValueError(f"chord, fillet radius and diameter must be positive, the diameter the largest, got {got}")
        return v

    @field_validator("load_sharing_factor")
    @classmethod
    def _kg(cls, v):
        if v is not None and not 1.0 <= v <= 3.0:
            raise ValueError(f"must lie in [1, 3], got {v}")
        return v

    @field_validator("dynamic_factors", "face_load_factors")
    @classmethod
    def _kv(cls, v):
        if v is not None and not all(1.0 <= k <= 10.0 for k in v):
            raise ValueError(f"must lie in [1, 10], got {list(v)}")
        return v

    @field_validator("ring_hardness")
    @classmethod
    def _hb(cls, v):
        if v is not None and not 100.0 <= v <= 700.0:
            raise ValueError(f"must lie in 100..700 HB, got {v}")
        return v

    @field_validator("root_radius")
    @classmethod
    def _rho(cls, v):
        if not all(0.0 < r <= 0.6 for r in v):
            raise ValueError(f"must lie in (0, 0.6] modules, got {list(v)}")
        return v


class PlanetaryDynamics(Spec):
    """Time integration of the stage's lumped torsional model with the time-varying stiffness of every
    sun-planet and ring-planet mesh (phased as the planets' positions dictate): the dynamic factor K_v of
    every mesh at the operating speed and, with ``sweep``, against speed."""

    speed: quantity("rad/s", gt=0) | None = None
    """Speed of the input member; none: rating.speed."""
    model: Literal["torsional", "lateral"] = "torsional"
    """The stage model integrated: "torsional" (rotations, the sun held on its axis) or "lateral" (the
    lateral-torsional model of [lateral]: translations on the bearings too, a floating sun; Lin & Parker 1999)."""
    stiffness_model: Literal["cai", "rectangular", "constant"] = "cai"
    """Shape of each mesh's time-varying stiffness about its mean (the stage's sun_planet_stiffness and
    ring_planet_stiffness), as for a gear train's mesh: "cai", "rectangular" or "constant"."""
    engagement: float = 0.0
    """Duration, in mesh periods, over which a tooth pair's stiffness ramps in and out (smoothstep; 0: a step; at most
    0.45)."""
    damping_ratio: float = 0.05
    """Mesh damping as a ratio of the critical damping of the mesh's two gears' reduced mass on its mean stiffness
    (in [0, 1))."""
    rating_kv: Literal["run", "method-b"] = "method-b"
    """K_v of the rating (when rating.dynamic_factors is not given): "method-b" (ISO 6336-1 method B; the run's K_v is
    reported beside it) or "run" (the largest over the planets, per mesh, from this integration at the rating's
    speed). The run's K_v is the largest mesh force over the largest quasi-static one (the load the planets pass
    between them as their stiffnesses vary is reported apart, as a time-varying K_gamma), but with a stiffness that
    steps (engagement 0) it holds the step response at any speed (NREL GRC stage 1 at 12.1 rpm: 1.54 / 1.28 against
    method B's 1.004 / 1.007; 1.001 / 1.003 with engagement 0.1), and the run has no pitch or profile deviations,
    which method B's K_v holds: so it is not the default."""
    step: quantity("s", gt=0) | None = None
    """Largest RK4 step; none: a twentieth of the period of the stage's highest mode."""
    steps_per_cycle: int = 64
    """RK4 steps per mesh period at least (16..10000)."""
    settle: quantity("s", gt=0) | None = None
    """Settling time before K_v is read; none: five decay times of the least damped mode, at most 0.5 s, and at
    least 20 mesh periods."""
    window_cycles: int = 20
    """Mesh periods over which K_v is read (2..10000)."""
    sweep: bool = False
    """Also run a speed sweep: K_v of every mesh against the input member's speed."""
    speed_min: quantity("rad/s", gt=0) | None = None
    """Lowest input speed of the sweep; none: speed_max / 100."""
    speed_max: quantity("rad/s", gt=0) | None = None
    """Highest input speed of the sweep; none: 1.3 x the speed where the mesh frequency meets the highest natural
    frequency."""
    count: int = 100
    """Number of speeds of the sweep (2..10000)."""

    _eng = field_validator("engagement")(classmethod(lambda cls, v: _engagement(v)))

    _zeta = field_validator("damping_ratio")(classmethod(lambda cls, v: _unit_interval(v)))

    _counts = model_validator(mode="after")(lambda self: _sweep_ranges(self))


class Planetary(Spec):
    """A simple planetary stage (sun, N planets on a carrier, ring; spur or helical gears, profile shifts
    allowed): mesh phasing, torsional (and, with ``lateral``, lateral-torsional) modes, static load
    sharing with pin position errors, and (with ``rating``) the ISO rating of every mesh."""

    sun_teeth: int
    """Number of teeth of the sun."""
    planet_teeth: int
    """Number of teeth of each planet."""
    module: quantity("m", gt=0)
    """Module of the stage (normal module of a helical stage)."""
    pressure_angle: quantity("rad", gt=0, lt=0.8) = 0.3490658503988659
    """Pressure angle of the basic rack (normal section of a helical stage; 20 deg: ISO 53)."""
    helix_angle: quantity("rad", ge=0, lt=0.7853981633974483) = 0.0
    """Helix angle of a helical stage (the sun of one hand, planets and ring of the other); 0: spur."""
    planets: int
    """Number of planets (1..24)."""
    planet_angles: Optional[list[quantity("rad")]] = None
    """Angular positions of the planets on the carrier; none: equally spaced (then (sun + ring teeth) / planets must
    be whole)."""
    sun_planet_stiffness: quantity("N/m", gt=0)
    """Mean mesh stiffness of each sun-planet mesh."""
    ring_planet_stiffness: quantity("N/m", gt=0)
    """Mean mesh stiffness of each ring-planet mesh."""
    sun_inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of the sun."""
    ring_inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of the ring."""
    carrier_inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of the carrier (without the planets)."""
    planet_inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of each planet about its own axis."""
    planet_mass: quantity("kg", gt=0)
    """Mass of each planet (it turns with the carrier)."""
    position_errors: list[quantity("m")] = []
    """Tangential pin position errors of the planets, one per planet (positive with the carrier's rotation; missing
    ones 0), for the static load sharing."""
    fixed: Literal["sun", "ring", "carrier"] = "ring"
    """The held member."""
    input: Literal["sun", "ring", "carrier"] = "sun"
    """The input member (not the held one)."""
    torque: quantity("N*m", gt=0)
    """Input torque on the input member."""
    ring_teeth: Optional[int] = None
    """Number of teeth of the ring; none: sun + 2 x planet teeth."""
    profile_shifts: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """Profile shift coefficients of sun, planet and ring (ISO 21771: ring d_a = d - 2 m (1 + x))."""
    centre_distance: Optional[quantity("m", gt=0)] = None
    """Working centre distance sun-planet; none: the sun-planet zero-backlash one."""
    lateral: Optional[PlanetaryLateral] = None
    """The lateral-torsional model's data (Lin & Parker); none: the torsional model only."""
    rating: Optional[PlanetaryRating] = None
    """ISO 6336-2/-3 rating of the stage's meshes; none: not rated."""
    dynamics: PlanetaryDynamics | None = None
    """Time integration of the stage with time-varying mesh stiffness (K_v of every mesh); none: not integrated."""
    output_gear: Optional[str] = None
    """A gear of the train on the stage's output shaft (a gearbox); give with output_shaft_stiffness."""
    output_shaft_stiffness: Optional[quantity("N*m/rad", gt=0)] = None
    """Torsional stiffness of the shaft from the stage's output member to output_gear."""

    @field_validator("sun_teeth", "planet_teeth", "ring_teeth")
    @classmethod
    def _z(cls, v):
        if v is not None and not 5 <= v <= 2000:
            raise ValueError(f"must lie in 5..2000, got {v}")
        return v

    @field_validator("profile_shifts")
    @classmethod
    def _x3(cls, v):
        if not all(-3.0 < x < 3.0 for x in v):
            raise ValueError(f"must lie in (-3, 3) modules, got {list(v)}")
        return v

    @field_validator("planets")
    @classmethod
    def _n(cls, v):
        # planetary stages carry 2 to 12 planets; 1 is an offset gear, not a stage
        if not 1 <= v <= 24:
            raise ValueError(f"must lie in 1..24, got {v}")
        return v

    @model_validator(mode="after")
    def _fit(self):
        import math

        n, zs, zp = self.planets, self.sun_teeth, self.planet_teeth
        zr = self.ring_teeth or zs + 2 * zp
        if zr - zp <= zs - 2:
            raise ValueError(f"ring_teeth: a ring of {zr} teeth cannot hold planets of {zp} around a sun of {zs}")
        if self.planet_angles is None:
            if (zs + zr) % n:
                raise ValueError(f"{n} planets cannot be equally spaced: (sun + ring teeth) / planets = "
                                 f"{zs + zr}/{n} is not a whole number; give planet_angles")
            psi = [2 * math.pi * i / n for i in range(n)]
        else:
            if len(self.planet_angles) != n:
                raise ValueError(f"planet_angles: {len(self.planet_angles)} angles for {n} planets")
            psi = sorted(a % (2 * math.pi) for a in self.planet_angles)
        # neighbouring planets must clear each other: centre chord above the planet's tip diameter
        m_t = self.module / math.cos(self.helix_angle)
        R = self.centre_distance or 0.5 * (zs + zp) * m_t
        d_tip = zp * m_t + (2 + 2 * self.profile_shifts[1]) * self.module
        gaps = [b - a for a, b in zip(psi, psi[1:])] + [2 * math.pi - psi[-1] + psi[0]] if n > 1 else []
        if gaps and 2 * R * math.sin(min(gaps) / 2) <= d_tip:
            raise ValueError(f"neighbouring planets overlap: centre distance {2e3 * R * math.sin(min(gaps) / 2):.4g} mm "
                             f"<= planet tip diameter {d_tip * 1e3:.4g} mm")
        if len(self.position_errors) > n:
            raise ValueError(f"position_errors: {len(self.position_errors)} values for {n} planets")
        if any(abs(e) > self.module for e in self.position_errors):
            raise ValueError("position_errors: a pin error above one module is not a position error")
        if self.fixed == self.input:
            raise ValueError(f"input and fixed are both {self.fixed!r}: the torque would go to ground")
        dyn = self.dynamics
        if dyn is not None and dyn.model == "lateral" and self.lateral is None:
            raise ValueError("dynamics.model: \"lateral\" integrates the lateral-torsional model: give [lateral] "
                             "(masses and bearing stiffnesses)")
        if dyn is not None and dyn.speed is None and self.rating is None:
            raise ValueError("dynamics.speed: give the input member's speed (or [rating] with its speed)")
        if dyn is not None and self.rating is not None and dyn.speed is not None and dyn.rating_kv == "run" \
                and self.rating.dynamic_factors is None and abs(dyn.speed - self.rating.speed) > 1e-9 * self.rating.speed:
            raise ValueError(f"dynamics.speed: the rating takes K_v from the run at its own speed "
                             f"{self.rating.speed:.9g} rad/s, got {dyn.speed:.9g} rad/s (remove dynamics.speed, or set "
                             "dynamics.rating_kv = \"method-b\")")
        if dyn is not None and self.helix_angle > 0 and self.rating is None:
            raise ValueError("dynamics: a helical stage's mesh stiffness needs the face width (give [rating] with "
                             "face_width)")
        if self.output_gear is not None and self.output_shaft_stiffness is None:
            raise ValueError("give output_gear and output_shaft_stiffness together (the train gear on the stage's "
                             "output shaft, and that shaft's stiffness)")
        return self


class Model(Spec):
    """A gear train: gears, meshes, shafts, operating point, integration, sweep, ISO data; or a
    planetary stage (``planetary``) analysed on its own."""

    kind: Literal["gear-train"]
    """The kind of model file: "gear-train"."""
    schema_version: Literal[1] = 1
    """Version of the model-file format (1)."""
    name: str = ""
    """A name for the train, shown in reports."""
    gears: list[Gear] = []
    """The gears of the train."""
    meshes: list[Mesh] = []
    """The meshes between pairs of gears."""
    shafts: list[Shaft] = []
    """Torsional shafts joining gears on one axis."""
    drive: Optional[Drive] = None
    """Operating point: input gear, speed and power or torque."""
    # a factory, not an instance: the limits its validator checks are read when a model loads, not at import
    simulation: Simulation = Field(default_factory=Simulation)
    """Time integration of the train."""
    sweep: Sweep = Sweep()
    """K_v against input speed."""
    iso: Iso = Iso()
    """ISO 6336 data: load factors, material, lubricant, roughness, life, minimum safety factors."""
    planetary: Optional[Planetary] = None
    """A planetary stage, analysed on its own or as the first stage of a gearbox."""
    stages: list[Planetary] = []
    """Further planetary stages in series after [planetary] (a gearbox)."""
    criteria: Criteria = Criteria()
    """Design limits of the verdict (criteria.py, docs/criteria.md)."""

    @model_validator(mode="after")
    def _topology(self):
        if self.stages and self.planetary is None:
            raise ValueError("stages: give [planetary] first, the gearbox's first stage")
        chain = [self.planetary, *self.stages] if self.planetary is not None else []
        if len(chain) > 1:
            self._chain(chain)
        if chain and chain[-1].output_gear is None and chain[-1].output_shaft_stiffness is not None:
            raise ValueError(f"{_where(len(chain) - 1)}.output_shaft_stiffness: the last stage drives no train "
                             "(give output_gear, or remove the stiffness)")
        if self.planetary is not None and not self.gears and not self.meshes and not self.shafts:
            return self           # planetary stages alone: no train to check
        if self.drive is None:
            raise ValueError("drive: a gear train needs [drive] (input, speed, power or torque)")
        names = [g.name for g in self.gears]
        for what, items in (("gears", self.gears), ("meshes", self.meshes), ("shafts", self.shafts)):
            seen = [i.name for i in items]
            dup = sorted({n for n in seen if seen.count(n) > 1})
            if dup:
                raise ValueError(f"{what}: duplicate name(s) {dup}")
        if not self.meshes:
            raise ValueError("meshes: a gear train needs at least one mesh")
        for k, link in enumerate([*self.meshes, *self.shafts]):
            where = f"meshes[{k}]" if k < len(self.meshes) else f"shafts[{k - len(self.meshes)}]"
            for g in link.gears:
                if g not in names:
                    raise ValueError(f"{where}.gears: no gear named {g!r} (gears: {', '.join(names)})")
        if self.drive.input not in names:
            raise ValueError(f"drive.input: no gear named {self.drive.input!r}")
        for k, g in enumerate(self.gears):
            # spur gears are a few to a few tens of modules wide, rarely wider than their pitch
            # diameter; 100 modules or 2 pitch diameters, whichever is larger, covers every real gear
            b_max = g.module * max(100, 2 * g.teeth)
            if g.face_width > b_max:
                raise ValueError(f"gears[{k}].face_width: {g.face_width:.4g} m is more than {b_max:.4g} m "
                                 f"(100 modules or 2 pitch diameters, whichever is larger)")
        if self.planetary is not None and [self.planetary, *self.stages][-1].output_gear is not None:
            self._gearbox(names)
        gear = self.gears[names.index(self.drive.input)]
        top = max(self.drive.speed, self.sweep.speed_max or 0.0)
        v = top * 0.5 * gear.module * gear.teeth
        if v > V_MAX:
            raise ValueError(f"drive.speed: a pitch-line speed of {v:.4g} m/s at the input gear is above "
                             f"{V_MAX:g} m/s (the fastest turbo gears run below 200 m/s)")
        return self

    def _gearbox(self, names):
        """A planetary stage driving the train: the train starts at the stage's output gear, with the
        torque (and, when the rating gives the stage's speed, the speed) the stage delivers."""
        from .planetary.gearbox import output_torque
        from .planetary.stage import MEMBERS, _speed_ratio, stage_of

        chain = [self.planetary, *self.stages]
        pl, where = chain[-1], _where(len(chain) - 1)
        if pl.output_gear not in names:
            raise ValueError(f"{where}.output_gear: no gear named {pl.output_gear!r} (gears: {', '.join(names)})")
        if self.drive.input != pl.output_gear:
            raise ValueError(f"drive.input: the train of a gearbox starts at the stage's output gear "
                             f"{pl.output_gear!r}, got {self.drive.input!r}")
        t_out = output_torque(pl)
        if self.drive.torque is None or abs(self.drive.torque - t_out) > 1e-6 * t_out:
            got = "power" if self.drive.torque is None else f"{self.drive.torque:.9g} N m"
            raise ValueError(f"drive.torque: the stage delivers {t_out:.9g} N m to {pl.output_gear!r} "
                             f"({where}.torque x speed ratio), got {got}")
        if pl.rating is not None:
            st = stage_of(pl)
            out = next(m for m in MEMBERS if m not in (pl.fixed, pl.input))
            w_out = pl.rating.speed / abs(_speed_ratio(st, pl.input, out))
            if abs(self.drive.speed - w_out) > 1e-6 * w_out:
                raise ValueError(f"drive.speed: the stage turns {pl.output_gear!r} at {w_out:.9g} rad/s "
                                 f"({where}.rating.speed / speed ratio), got {self.drive.speed:.9g} rad/s")

    def _chain(self, chain):
        """Planetary stages in series: each but the last drives the next one's input member through its
        output shaft, with the torque (and, with ratings, the speed) it delivers."""
        from .planetary.gearbox import output_speed, output_torque

        for k, (a, b) in enumerate(zip(chain, chain[1:])):
            wa, wb = _where(k), _where(k + 1)
            if a.output_gear is not None:
                raise ValueError(f"{wa}.output_gear: only the last stage drives the train; this one drives {wb}")
            if a.output_shaft_stiffness is None:
                raise ValueError(f"{wa}.output_shaft_stiffness: this stage drives {wb} through its output shaft: "
                                 "give the shaft's torsional stiffness")
            t = output_torque(a)
            if abs(b.torque - t) > 1e-6 * t:
                raise ValueError(f"{wb}.torque: the stage before delivers {t:.9g} N m ({wa}.torque x speed ratio), "
                                 f"got {b.torque:.9g} N m")
            if a.rating is not None and b.rating is not None:
                w = output_speed(a)
                if abs(b.rating.speed - w) > 1e-6 * w:
                    raise ValueError(f"{wb}.rating.speed: the stage before turns it at {w:.9g} rad/s "
                                     f"({wa}.rating.speed / speed ratio), got {b.rating.speed:.9g} rad/s")


def _where(k: int) -> str:
    """The model-file path of stage ``k`` of a gearbox (0: [planetary], then [[stages]])."""
    return "planetary" if k == 0 else f"stages[{k - 1}]"

