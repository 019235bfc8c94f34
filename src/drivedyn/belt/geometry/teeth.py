"""A synchronous belt's teeth as the drive sees them: tooth count, pitch, the tooth spring, its play
and the climb factor, from the model's ``belt.teeth`` and the profile catalogue
(mechanics/teeth). The segment model's tooth contact (segments/_teeth.py) and check read them here.

Where the model leaves the play or the flank angle out, both come from the exact contours of the
profile pair on the smallest toothed pulley, as the toothed-mesh analysis finds them (seed 001):
the seated tooth lifted out of its groove while pressed sideways (loadshare.exit_path); its sideways
freedom at the seat is the play, the steepest contact angle on the way out the flank angle."""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from ...core.errors import ModelError


@dataclass(frozen=True)
class BeltTeeth:
    profile: str            # catalogue name
    pitch: float            # p, the belt's nominal pitch (m)
    count: int              # teeth on the belt
    count_source: str       # where the count came from
    stiffness: float        # k_t, one tooth, whole width (N/m)
    stiffness_source: str
    play: float             # sideways play of a seated tooth (m), the spring's dead band (full width)
    play_source: str
    flank_angle: float      # phi (rad)
    flank_source: str
    climb: float            # tan(phi - rho), 0: self-locking (no jump)
    nodes: int              # segments per tooth
    damping_ratio: float

    def summary(self) -> dict:
        """The belt's tooth data as a run's summary["teeth"] opens (both dynamic models' teeth outputs)."""
        return {"profile": self.profile, "pitch": self.pitch, "count": self.count, "count_source": self.count_source,
                "tooth_stiffness": self.stiffness, "tooth_stiffness_source": self.stiffness_source, "play": self.play,
                "play_source": self.play_source, "flank_angle": self.flank_angle, "flank_angle_source": self.flank_source,
                "climb_factor": self.climb, "pulleys": {}}


@functools.lru_cache(maxsize=32)
def _pair_data(profile: str, z: int) -> tuple[float, float]:
    """(play, flank angle) of the catalogue profile on its standard groove of z teeth."""
    from ...mechanics.teeth import catalogue
    from ...mechanics.teeth.loadshare import exit_path, flank_angle
    from ...mechanics.teeth.pair import build

    tooth = catalogue.tooth(profile)
    kind = "standard" if catalogue.groove(profile, z) is not None else "generated"
    pair = build(tooth, profile, None, z, kind, None, 0.0, 0.0, 2e-7, 2e-5, label=f"{profile} z{z}")
    path = exit_path(pair)
    play = float(path[1][0]) if math.isfinite(path[1][0]) else 0.0
    return play, float(flank_angle(pair, path=path))


def belt_teeth(model, path_length: float | None = None) -> BeltTeeth | None:
    """The belt's teeth (None for a friction belt); ``path_length``: the drawn path's length, for a
    belt given by its pretension and no tooth count."""
    t = model.belt.teeth
    if t is None:
        return None
    from ...mechanics.teeth import catalogue
    from ...mechanics.teeth.loadshare import climb_factor, tooth_stiffness_per_width

    name = catalogue.canonical(t.profile)
    p = catalogue.entry(name).pitch
    if t.count is not None:
        count, csrc = t.count, "belt.teeth.count"
    elif model.belt.length is not None:
        count, csrc = round(model.belt.length / p), "belt.length / pitch"
    else:
        if path_length is None:
            from ...mechanics.layout import compute_layout

            path_length = compute_layout(model).length
        count, csrc = round(path_length / p), "the drawn path's length / pitch, rounded"
    zs = [q.teeth for q in model.pulleys if q.teeth]
    need_pair = t.play is None or t.flank_angle is None or t.tooth_stiffness is None
    try:
        tooth = catalogue.tooth(name) if need_pair else None
    except ValueError as exc:
        raise ModelError(f"{exc}: give tooth_stiffness, play and flank_angle", field="belt.teeth") from None
    if t.tooth_stiffness is not None:
        k, ksrc = t.tooth_stiffness, "belt.teeth.tooth_stiffness"
    else:
        k = tooth_stiffness_per_width(tooth, t.tooth_modulus) * t.width
        ksrc = f"the {name} tooth's shape, G = {t.tooth_modulus / 1e6:.3g} MPa, width {t.width * 1e3:.4g} mm"
    if t.play is None or t.flank_angle is None:
        try:
            play, phi = _pair_data(name, min(zs))
        except ValueError as exc:
            raise ModelError(f"the {name} pair on {min(zs)} grooves: {exc}", field="belt.teeth") from None
        except Exception as exc:  # noqa: BLE001  (a contour the geometry library cannot intersect: say so)
            raise ModelError(f"the {name} pair on {min(zs)} grooves: its contours could not be intersected "
                             f"({type(exc).__name__}: {str(exc).splitlines()[0][:120]}); give belt.teeth.play and "
                             "belt.teeth.flank_angle", field="belt.teeth") from None
        pair_src = f"the {name} pair's contours on {min(zs)} grooves"
    play_, psrc = (t.play, "belt.teeth.play") if t.play is not None else (play, pair_src)
    phi_, fsrc = (t.flank_angle, "belt.teeth.flank_angle") if t.flank_angle is not None else (phi, pair_src)
    if play_ >= p / 2:
        raise ModelError(f"{play_ * 1e3:.4g} mm of sideways play is at least half the {p * 1e3:.4g} mm pitch",
                         field="belt.teeth.play")
    return BeltTeeth(name, p, int(count), csrc, float(k), ksrc, float(play_), psrc, float(phi_), fsrc,
                     climb_factor(phi_, t.flank_friction), t.nodes_per_tooth, t.damping_ratio)


def chain_radius(radius: float, model) -> float:
    """The contact radius at which the segment model's chain of straight segments carries its teeth at
    the grooves' spacing: a segment of length l whose centre rides at radius r_c spans 2 atan(l / 2 r_c)
    of the pulley, the arc l / r of the belt's pitch line when r_c = r x / tan x, x = l / 2r
    (l = pitch / nodes_per_tooth). Riding at the pitch radius itself the chain's teeth would fall short
    of their grooves by p^3 / (12 m^2 r^2) per pitch (0.05 mm on a 22-groove HTD 8M pulley at one
    segment per tooth): a polygon effect, not the belt's physics. The chain's length per tooth on the
    wrap is then the pitch, as the belt's."""
    from ...mechanics.teeth import catalogue

    t = model.belt.teeth
    x = catalogue.entry(t.profile).pitch / t.nodes_per_tooth / (2 * radius)
    return radius * x / math.tan(x)


def sinking(contact, pressure: float) -> tuple[float, float]:
    """(delta, k_r): how far the belt's cord sinks into its support under the wrap's pressure T / R
    (N/m) by the contact law (``contact``: the model's, per length: stiffness_linear c2 p +
    stiffness_quadratic c1 p^2), and the law's tangent there, c2 + 2 c1 delta (N/m^2): the radial
    stiffness of mechanics/teeth/loadshare.py's eq. 4."""
    from .placement import penetration

    c1, c2 = contact.stiffness_quadratic, contact.stiffness_linear
    delta = float(penetration(pressure, c1, c2))
    return delta, c2 + 2 * c1 * delta


def installed_tension(model, layout, placed: float) -> float:
    """The tension at which a toothed belt's cord runs on the pitch circles as installed: a belt given
    by its length, that length stretched onto the pitch path (the continuum's, EA strain^e, not the
    segment chain's placement, whose polygon moves it by O(l^2)); else ``placed`` (the pretension)."""
    b = model.belt
    if b.length is None:
        return placed
    strain = max(layout.length / b.length - 1.0, 0.0)
    return b.axial_stiffness * strain ** b.axial_exponent
