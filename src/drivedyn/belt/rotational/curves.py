"""Non-circular pulleys (``pulleys[].pitch_curve``) in the rotational model: the belt path on the
turning curves, tabulated over one period of each curve's angle.

A grooved curve carries the belt on its pitch line, one belt pitch per groove, so the belt that passes a
tangent point is the arc the turning curve moves past it: with S(theta) the arc position on the curve
(mechanics/pitch_curves.py: ``cumulative``) of the tangent point where the belt arrives (or leaves) at
the pulley's angle theta, the flux is sigma dS / dt of it, which on a circle is r omega. The span's
pull acts on its lever arm, the effective radius h (the span line's distance from the centre), so the
pulley's torque is h_out T_out - h_in T_in. Span lengths, directions, wraps and the effective radii are
the common tangents of mechanics/curve_layout.py at each tabulated angle, the other pulleys at their
rest angles (a span between two curves would need both angles: refused); the kernel reads them by a
periodic cubic (rotational/_kernels.py: ``_curve_geometry``). The tensioners' travel tables stay those of
the circles and the two add (the travel's effect on the curves' tangents is of second order).

A smooth (friction) curve carries its wrap's belt stuck to its rim past the two tangent points at their
own rates, the arcs dS_in and dS_out its turn moves past them (the wrap's arc, tabulated too, changes by
their difference): the elastic-plastic law's cells are carried by dS_in at the entry and stretched to
the new arc (rotational/_kernels.py: ``_cell_transport_curve``, each cell its own cubic); with
Threlfall's law the steady content follows the arc at once and only creep's unsettled part relaxes over
a passage. The belt's speed at a tangent point is the flux's plus the point's own motion along its span
(omega h less dS / dt), which the creep power books.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import ModelError

#: table nodes over one period of a curve's angle: the cubic's error falls as (2 pi / (order N))^4; an
#: oval of order 2 and ovality 0.04 at 96 nodes moves its span lengths by 3e-11 m against 192
NODES = 96


@dataclass(frozen=True)
class Curves:
    """The tables (rotational/_kernels.Rot's c* fields) and what the rest state needs."""

    fields: dict
    pulleys: list          # pulley index per curve
    base: object           # mechanics.curve_layout.CurveLayout at the rest angles

    @property
    def arcs0(self) -> np.ndarray:
        """(nk,) belt on each pulley at the rest angles (m)."""
        return np.array(self.base.arc)

    @property
    def spans0(self) -> np.ndarray:
        """(nspan,) span lengths at the rest angles (m)."""
        return self.base.span_lengths


def empty_fields(nk, ns) -> dict:
    z = np.zeros
    return dict(cpul=np.zeros(0, dtype=np.int64), cP=z(0), csig=z(0), cper=z(0), cL=z((0, 4, ns)), cdx=z((0, 4, ns)),
                cdy=z((0, 4, ns)), cw=z((0, 4, nk)), crin=z((0, 4)), crout=z((0, 4)), cse=z((0, 4)), csx=z((0, 4)),
                ct0=z((0, 4, ns)), ct1=z((0, 4, ns)), cA=z((0, 4)), cW=z((0, 4)))


def kernel_fields(curves: Curves | None, nk, ns) -> dict:
    return curves.fields if curves is not None else empty_fields(nk, ns)


def period(q) -> float:
    """The period of a pulley's geometry in its angle (rad): an oval's of order n repeats after 2 pi / n."""
    return 2 * math.pi / q.pitch_curve.order if q.pitch_curve.kind == "oval" else 2 * math.pi


def tables(model, lay) -> Curves | None:
    """The curves' tables about the circle layout ``lay`` (its centres: the tensioners at rest)."""
    from ...mechanics.curve_layout import layout_at
    from ..steady.modes import rolled_on

    ps = model.pulleys
    idx = [j for j, q in enumerate(ps) if q.pitch_curve is not None]
    if not idx:
        return None
    nk = len(ps)
    for j in idx:
        if not ps[j].teeth and model.friction.radius == "centre":
            raise ModelError(f"pulley {ps[j].name!r}: the rotational model reads a smooth pitch curve's friction at its "
                             "contact radius: friction.radius = \"centre\" (the belt's depth in the groove) is not "
                             "modelled on a turning curve; leave friction.radius out", field="friction.radius")
        for other in ((j - 1) % nk, (j + 1) % nk):
            if other in idx and other != j:
                raise ModelError(f"pulleys {ps[j].name!r} and {ps[other].name!r} are both non-circular and share a span: the "
                                 "rotational model tabulates one curve per span", field=f"pulleys[{other}].pitch_curve")
    names = [q.name for q in ps]
    sides = [q.side for q in ps]
    curves = [q.curve for q in ps]
    base = layout_at(names, lay.centers, curves, sides, orientation=lay.orientation)
    L_c = np.array([sp.length for sp in lay.spans])
    d_c = np.array([[math.cos(sp.angle), math.sin(sp.angle)] for sp in lay.spans])
    ns = len(lay.spans)
    f = empty_fields(nk, ns)
    nc = len(idx)
    f.update(cpul=np.array(idx, dtype=np.int64), cP=np.zeros(nc), csig=np.zeros(nc), cper=np.zeros(nc),
             cL=np.zeros((nc, NODES, ns)), cdx=np.zeros((nc, NODES, ns)), cdy=np.zeros((nc, NODES, ns)),
             cw=np.zeros((nc, NODES, nk)), crin=np.zeros((nc, NODES)), crout=np.zeros((nc, NODES)),
             cse=np.zeros((nc, NODES)), csx=np.zeros((nc, NODES)), ct0=np.zeros((nc, NODES, ns)),
             ct1=np.zeros((nc, NODES, ns)), cA=np.zeros((nc, NODES)), cW=np.zeros((nc, NODES)))
    for a, j in enumerate(idx):
        P = period(ps[j])
        c = curves[j]
        per = c.perimeter / (2 * math.pi)
        f["cP"][a], f["cper"][a] = P, per
        f["csig"][a] = 1.0 if lay.rho[j] > 0 else -1.0
        for i in range(NODES):
            th = i * P / NODES
            angles = np.zeros(nk)
            angles[j] = th
            cl = layout_at(names, lay.centers, curves, sides, angles=angles, orientation=lay.orientation)
            f["cL"][a, i] = np.array([sp.length for sp in cl.spans]) - L_c
            d = np.array([[math.cos(sp.angle), math.sin(sp.angle)] for sp in cl.spans])
            f["cdx"][a, i], f["cdy"][a, i] = d[:, 0] - d_c[:, 0], d[:, 1] - d_c[:, 1]
            f["cw"][a, i] = cl.wrap - lay.wrap
            f["cA"][a, i] = cl.arc[j]
            f["cW"][a, i] = cl.wrap[j]
            f["crin"][a, i] = cl.spans[j - 1].radius1
            f["crout"][a, i] = cl.spans[j].radius0
            # arc positions of the tangent points (own angle psi - theta: S falls by perimeter / 2 pi per radian
            # on average), that drift taken off
            f["cse"][a, i] = c.cumulative(cl.spans[j - 1].phi1) + per * th
            f["csx"][a, i] = c.cumulative(cl.spans[j].phi0) + per * th
            # the circles' tangent points move round them as the curve turns: the belt rolled onto them
            # (steady/modes.rolled_on; the curve's own ends are its fluxes'), from the rest angles
            r0, r1 = rolled_on(base, cl)
            r0[j], r1[(j - 1) % nk] = 0.0, 0.0
            f["ct0"][a, i], f["ct1"][a, i] = r0, r1
        # the own angles are continuous over the table, but a support point may be returned a turn away
        for key in ("cse", "csx"):
            row = f[key][a]
            row -= c.perimeter * np.round((row - row[0]) / c.perimeter)
    return Curves(f, idx, base)


def rest_tension(model, curves: Curves, L0) -> float:
    """The uniform tension at rest (N) at which the path on the curves at their rest angles holds the
    unstretched belt L0: rest.tension_at on that layout (the belt sunk into the smooth pulleys)."""
    from ..geometry.rest import tension_at

    return tension_at(model, curves.base, L0)
