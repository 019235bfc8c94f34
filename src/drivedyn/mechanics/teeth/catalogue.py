"""The profile catalogue: belt teeth and standard pulley grooves with the source of every number.

Numbers are the ones gathered in shared/design/toothed-profiles.md (mm there, metres here).
Source keys (full references in that note and in the README section on meshing):

- OPT: Optibelt technical manual, table 2 "according to ISO 5296" (trapezoidal teeth)
- SDP: SDP/SI handbook D265, table 4 (PLD a) and fig. 19 (T profiles)
- NS: nothson.com, ISO 5294 groove table (trapezoidal grooves, 2a)
- SATI: SATI/Synchroflex DIN 7721-2 groove table (T grooves, SE for z <= 20, N for z >= 21)
- TB: transbelting.com HTD page (HTD tooth height, PLD)
- FCG: freecad.gears HTD/GT tooth construction (arc radii, fillets)
- CS: camsoft.it HTD groove table (width, depth, radii, 14 deg flanks)

Where the sources conflict the choice is written beside the entry. Profiles whose shape no
accessible source gives (AT5, AT10, T20 tooth) are listed so that asking for them gets a clear
message instead of "unknown profile".
"""
from __future__ import annotations

import difflib
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from .profiles import ArcGroove, ArcTooth, GTTooth, TrapezoidalGroove, TrapezoidalTooth

MM = 1e-3
DEG = np.pi / 180


@dataclass(frozen=True)
class Entry:
    """A catalogue profile: its belt tooth, its standard groove (a function of the tooth count)
    and, when incomplete, why."""

    name: str
    family: str
    pitch: float
    tooth: Optional[object]
    groove: Optional[Callable[[int], object]]
    source: str
    missing: str = ""


def _iso5296(name, p, ang, s, ht, rr, ra, hs, a, groove, note=""):
    """Trapezoidal belt (ISO 5296 via OPT, a from SDP/NS) with its ISO 5294 groove (NS)."""
    src = f"tooth ISO 5296 (OPT table 2), PLD SDP table 4 / NS; groove ISO 5294 (NS){note}"
    tooth = TrapezoidalTooth(pitch=p * MM, height=ht * MM, pld=a * MM, thickness=hs * MM, width=s * MM,
                             angle=ang * DEG, tip_radius=ra * MM, root_radius=rr * MM, source=src, name=name)
    bw, hg, phi, rb, rt = groove
    g = TrapezoidalGroove(pitch=p * MM, depth=hg * MM, pld=a * MM, bottom_width=bw * MM, angle=phi * DEG,
                          bottom_radius=rb * MM, tip_radius=rt * MM, source="ISO 5294 (NS)", name=name)
    return Entry(name, "trapezoidal ISO 5296", p * MM, tooth, lambda z: g, src)


def _din7721(name, p, s, ht, r, hs, a, n, se, rk, rf):
    """T profile (DIN 7721-1 via SDP fig. 19) with the DIN 7721-2 groove: SE for z <= 20, N above (SATI)."""
    src = "tooth DIN 7721-1 (SDP fig. 19, JA agrees), PLD SDP table 4; groove DIN 7721-2 (SATI)"
    tooth = TrapezoidalTooth(pitch=p * MM, height=ht * MM, pld=a * MM, thickness=hs * MM, width=s * MM,
                             angle=40 * DEG, tip_radius=r * MM, root_radius=r * MM, source=src, name=name)

    def groove(z):
        depth, bottom = se if z <= 20 else n
        return TrapezoidalGroove(pitch=p * MM, depth=depth * MM, pld=a * MM, bottom_width=bottom * MM,
                                 angle=25 * DEG, bottom_radius=rf * MM, tip_radius=rk * MM,
                                 source=f"DIN 7721-2 {'SE' if z <= 20 else 'N'} (SATI)", name=name)

    return Entry(name, "trapezoidal DIN 7721", p * MM, tooth, groove, src)


def _htd(name, p, ht, hs, a, rt_arc, fillet, groove, note=""):
    """HTD tooth (TB heights, FCG arc construction) with the HTD groove (CS, 14 deg flanks)."""
    family = "curvilinear HTD (ISO 13050 H)" if "scaled" not in note else "HTD 8M scaled (not a standard)"
    src = "tooth TB (height, PLD) + FCG (arc radius, fillet); groove CS" + note
    tooth = ArcTooth(pitch=p * MM, height=ht * MM, pld=a * MM, thickness=hs * MM, arc_radius=rt_arc * MM,
                     root_radius=fillet * MM, source=src, name=name)
    w, depth, rb, rt = groove
    g = ArcGroove(pitch=p * MM, depth=depth * MM, pld=a * MM, width=w * MM, angle=14 * DEG,
                  bottom_radius=rb * MM, tip_radius=rt * MM, source="CS" + note, name=name)
    return Entry(name, family, p * MM, tooth, lambda z: g, src)


def _gt(name, p, ht, hs, a, tip, flank, offset, fillet):
    src = "Gates PowerGrip GT as drawn in FCG (BP, NOP agree); no standard groove published"
    tooth = GTTooth(pitch=p * MM, height=ht * MM, pld=a * MM, thickness=hs * MM, tip_radius=tip * MM,
                    flank_radius=flank * MM, flank_offset=offset * MM, root_radius=fillet * MM, source=src, name=name)
    return Entry(name, "curvilinear GT (ISO 13050 G)", p * MM, tooth, None, src)


def _missing(name, family, p, why):
    return Entry(name, family, p * MM, None, None, "", missing=why)


_ENTRIES = [
    #         name   p       2beta s      ht    rr    ra    hs    a       groove (bw, hg, phi, rb, rt)
    _iso5296("MXL", 2.032, 40, 1.14, 0.51, 0.13, 0.13, 1.2, 0.254, (0.84, 0.69, 20, 0.35, 0.13)),
    _iso5296("XL", 5.080, 50, 2.57, 1.27, 0.38, 0.38, 2.3, 0.254, (1.32, 1.65, 25, 0.41, 0.64),
             note="; XL flanks are 50 deg, not 40"),
    _iso5296("L", 9.525, 40, 4.65, 1.91, 0.51, 0.51, 3.6, 0.381, (3.05, 2.67, 20, 1.19, 1.17)),
    _iso5296("H", 12.700, 40, 6.12, 2.29, 1.02, 1.02, 4.0, 0.686, (4.19, 3.05, 20, 1.60, 1.60)),
    _iso5296("XH", 22.225, 40, 12.57, 6.35, 1.57, 1.19, 11.2, 1.397, (7.90, 7.14, 20, 1.98, 2.39)),
    _iso5296("XXH", 31.750, 40, 19.05, 9.53, 2.29, 1.52, 15.7, 1.524, (12.17, 10.31, 20, 3.96, 3.18)),
    #         name    p    s     ht   r    hs   a    N (H_R, K_R)  SE (H_R, K_R)  r_k  r_f
    _din7721("T2.5", 2.5, 1.5, 0.7, 0.2, 1.3, 0.3, (1.0, 0.9), (0.75, 1.0), 0.3, 0.2),
    _din7721("T5", 5.0, 2.65, 1.2, 0.4, 2.2, 0.5, (1.95, 1.50), (1.25, 1.80), 0.6, 0.4),
    _din7721("T10", 10.0, 5.3, 2.5, 0.6, 4.5, 1.0, (3.40, 3.40), (2.60, 3.60), 0.8, 0.6),
    _missing("T20", "trapezoidal DIN 7721", 20.0, "the T20 tooth width s was not found in any accessible "
             "source; define the tooth in the model file ([belt.tooth])"),
    _missing("AT5", "trapezoidal DIN 7721 AT", 5.0, "AT5 flank angle, width and radii were not found in any "
             "accessible source; define the tooth and groove in the model file"),
    _missing("AT10", "trapezoidal DIN 7721 AT", 10.0, "AT10 flank angle, width, radii and PLD were not found in "
             "any accessible source; define the tooth and groove in the model file"),
    #     name      p   ht    hs   a      R     fillet  groove (w at OD, depth, R, rt)
    _htd("HTD3M", 3, 1.21, 2.4, 0.381, 0.89, 0.26, (1.90, 1.22, 0.91, 0.30)),
    # 5M: CS depth 2.06 is below the TB tooth height 2.08 (Gates 2.06): NS depth 2.16 is used.
    _htd("HTD5M", 5, 2.08, 3.8, 0.572, 1.49, 0.43, (3.25, 2.16, 1.56, 0.48),
         note="; depth NS 2.16 (CS 2.06 is below the tooth height 2.08)"),
    _htd("HTD8M", 8, 3.38, 6.0, 0.686, 2.46, 0.70, (5.35, 3.451, 2.57, 0.80),
         note="; depth 3.451 (CS) rather than NS 3.54"),
    # 14M: arc radius and fillet not published (n/f): scaled from 8M by 14/8 (assumption).
    # CS depth 6.00 is below the tooth height 6.02, which cannot seat: NS depth 6.20 is used.
    _htd("HTD14M", 14, 6.02, 10.0, 1.397, 2.46 * 14 / 8, 0.70 * 14 / 8, (9.80, 6.20, 4.65, 1.40),
         note="; 14M arc radius and fillet scaled from 8M by 14/8 (not published); depth NS 6.20 "
              "(CS 6.00 is below the tooth height)"),
    # Not a standard: the HTD 8M tooth and groove scaled by 9.525/8 to the L pitch, for the seed's
    # mixed pair at equal pitch (an L belt on an HTD-form pulley of the same pitch).
    # Every length of the 8M entry (TB/FCG tooth, CS groove, PLD) times 9.525/8; angles unchanged.
    _htd("HTD9.525", 9.525, *(x * 9.525 / 8 for x in (3.38, 6.0, 0.686, 2.46, 0.70)),
         tuple(x * 9.525 / 8 for x in (5.35, 3.451, 2.57, 0.80)),
         note="; HTD 8M tooth and groove scaled by 9.525/8 (not a standard profile)"),
    #    name     p   ht    hs    a       tip    flank (offset)  fillet
    _gt("GT2-2M", 2, 0.75, 1.38, 0.254, 0.555, 1.00, 0.40, 0.15),
    _gt("GT2-3M", 3, 1.14, 2.40, 0.381, 0.85, 1.52, 0.61, 0.25),
    _gt("GT2-5M", 5, 1.93, 3.81, 0.5715, 1.44, 2.57, 1.03, 0.416),
]

CATALOGUE = {e.name: e for e in _ENTRIES}

_ALIASES = {"HTD9525": "HTD9.525", "3M": "HTD3M", "5M": "HTD5M", "8M": "HTD8M", "14M": "HTD14M",
            "2MGT": "GT2-2M", "3MGT": "GT2-3M", "5MGT": "GT2-5M", "GT2": "GT2-2M",
            "GT22M": "GT2-2M", "GT23M": "GT2-3M", "GT25M": "GT2-5M"}


def _key(name: str) -> str:
    return "".join(ch for ch in str(name).upper() if ch not in " _-")


_INDEX = {_key(n): n for n in CATALOGUE} | {_key(a): n for a, n in _ALIASES.items()}


def canonical(name: str) -> str:
    """The catalogue name of ``name`` ("htd 8m" -> "HTD8M"); ValueError with a suggestion if unknown."""
    k = _key(name)
    if k in _INDEX:
        return _INDEX[k]
    close = difflib.get_close_matches(k, list(_INDEX), n=1, cutoff=0.5)
    hint = f" (did you mean {_INDEX[close[0]]!r}?)" if close else ""
    raise ValueError(f"unknown profile {name!r}{hint}; known: {', '.join(CATALOGUE)}")


def entry(name: str) -> Entry:
    """The catalogue entry of ``name``."""
    return CATALOGUE[canonical(name)]


def tooth(name: str):
    """The belt tooth of a catalogue profile; ValueError if its shape is not known."""
    e = entry(name)
    if e.tooth is None:
        raise ValueError(f"profile {e.name!r} has no tooth shape: {e.missing}")
    return e.tooth


def groove(name: str, z: int):
    """The standard groove of a catalogue profile for ``z`` teeth, or None if none is defined."""
    e = entry(name)
    return None if e.groove is None else e.groove(z)


#: Tension-member stiffness EA per unit belt width (N per m of width), where a source gives it:
#: ELATECH "specific spring rate" C_spez (polyurethane belts with steel cord; ELA in
#: shared/design/toothed-profiles.md): T5 90 000 N at 10 mm (catalogue p. 8), HTD 3M 80 000 N at
#: 10 mm, T2.5 6.0e3-7.5e3 N/mm (lower value kept; BRE gives 2.45e3). Rubber belts with glass cord
#: (the seed's automotive L and HTD belts) differ; no source for them was found, so the model
#: file must give ``load.cord_stiffness`` for every other profile.
CORD_STIFFNESS = {
    "T5": (9.0e6, "ELATECH C_spez 90 000 N / 10 mm (polyurethane, steel cord)"),
    "HTD3M": (8.0e6, "ELATECH C_spez 80 000 N / 10 mm (polyurethane, steel cord)"),
    "T2.5": (6.0e6, "ELATECH C_spez 6.0e3-7.5e3 N/mm (lower kept; BRE 2.45e3) (polyurethane, steel cord)"),
}


def cord_stiffness(name):
    """(EA per unit width in N/m, source) of a catalogue profile, or None if no source gives it."""
    if name is None:
        return None
    return CORD_STIFFNESS.get(canonical(name))
