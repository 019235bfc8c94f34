"""The belt as the part: a ribbed belt named by its part number (profile, ribs, effective length,
belt.effective_length) installs the drive. Its tensioner sits where the layout's required belt
length equals the belt's effective length (positions.py: the table's "installed" position,
as a supplier's report finds its rows from belt lengths), and the belt there carries the tension
the spring holds at that position (frictionless virtual work). The unstretched belt that this
installation holds (the path over 1 + T/EA, less the belt sunk into the grooves: rest.py) is the
``belt.length`` both dynamic models, the steady state and check start from.

With ``belt.pretension`` or ``belt.length`` given, those install the belt instead (drives without a
part number); the part's position and tension are then still reported, with a warning where they
differ from the installation's."""
from __future__ import annotations

from ...core.errors import ModelError


def part_table(drive):
    """The position table of the drive's supplier tensioner (positions.position_tables), or None."""
    from .positions import position_tables

    tables = position_tables(drive)
    return tables[0] if tables else None


def part_length(drive) -> float:
    """Unstretched belt length (m) that the part installs: the belt at the table's installed
    position, at its tension. ModelError (naming the field) where the part cannot install it."""
    from . import tensioner as TN
    from ...mechanics.layout import compute_layout
    from .rest import belt_content

    model = drive.model
    table = part_table(drive)
    if table is None:
        raise ModelError("the belt's effective length installs the belt only with a supplier tensioner (an arm with "
                         "free_angle, free_torque and rate): give belt.pretension or belt.length",
                         field="belt.effective_length")
    if table.installed is None:
        raise ModelError(f"belt.effective_length: the tensioner {table.pulley!r} cannot hold this belt: "
                         f"{table.unreached['installed']}", field="belt.effective_length")
    j = [p.name for p in model.pulleys].index(table.pulley)
    lay = compute_layout(TN.with_centres(model, {j: table.installed.centre}))
    return belt_content(model, lay, table.installed.tension)


def length_warnings(drive, table) -> list[str]:
    """Warnings where the drawn layout or the installation disagree with the part: the drawn tensioner
    position needing a belt outside the part's tolerance band, a pretension other than the part's."""
    import math

    out = []
    belt = drive.model.belt
    L = belt.effective_length
    if L is None or table is None:
        return out
    drawn = table.drawn_length
    if math.isfinite(drawn) and abs(drawn - L) > belt.length_tolerance:
        where = (f"the tensioner sits {math.degrees(abs(table.installed.rel - table.rows[3].rel)):.1f} deg of arm "
                 f"from the drawn position, at {table.installed.tension:.1f} N" if table.installed is not None
                 else "the tensioner cannot hold it")
        out.append(f"the drawn layout needs a {drawn * 1e3:.1f} mm belt (required effective length at the drawn "
                   f"tensioner), the part is {L * 1e3:.1f} mm +- {belt.length_tolerance * 1e3:.1f} mm: {where}")
    if belt.pretension is not None and table.installed is not None \
            and abs(belt.pretension / table.installed.tension - 1) > 0.01:
        out.append(f"belt.pretension {belt.pretension:.1f} N installs the belt; the part ({L * 1e3:.1f} mm) at its "
                   f"tensioner position holds {table.installed.tension:.1f} N: leave belt.pretension out to install "
                   "the part")
    return out
