"""The drive resolved once from its model: what the steady mechanics, the check report and both
dynamic models start from, instead of each re-deriving it from the raw model.

``resolve(model)`` lays the drive out as drawn and finds its tensioners and the sense of travel
that tensions the belt; the rest is computed the first time it is asked for and kept (the object is
frozen; ``functools.cached_property`` fills each field once):

- ``resolved``: the model with ``belt.segments = "auto"`` resolved to a count (segment_count.py);
- ``equilibrium``: the tensioners' static equilibrium with the belt placed as the segment model
  places it (tensioner.equilibrium; None without tensioners): the segment model and ``check``;
- ``installed_length``, ``rest``: the unstretched belt length and the continuum's rest state
  (rest.py): the rotational model and the modes.

A belt given by its part number alone (belt.effective_length, no pretension or length) is
installed here: ``model`` then carries the unstretched length the part installs (part.py).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from . import tensioner
from ...mechanics.layout import Layout, compute_layout
from .rest import installed_length, rest_state
from .segment_count import resolved


@dataclass(frozen=True)
class Drive:
    """A belt drive resolved from ``model`` (build it with :func:`resolve`)."""

    model: object                  # the model as given (belt.segments may be "auto")
    layout: Layout                 # the layout as drawn
    tensioners: tuple              # indices of the pulleys a tensioner carries
    senses: tuple                  # per tensioner, +-1: the sense of travel that lengthens the belt's path

    @cached_property
    def resolved(self):
        """The model with ``belt.segments`` a count."""
        return resolved(self.model)

    @cached_property
    def equilibrium(self):
        """tensioner.Equilibrium at rest with the segment model's placement, or None without tensioners."""
        if not self.tensioners:
            return None
        return tensioner.equilibrium(self.resolved, self.layout, list(self.senses))

    @cached_property
    def installed_length(self) -> float:
        """Unstretched belt length (m) of the continuum (rest.installed_length)."""
        return installed_length(self.model, self.layout)

    @cached_property
    def rest(self):
        """(travel per tensioner, uniform tension at rest, layout there) of the continuum (rest.rest_state)."""
        return rest_state(self.model, self.installed_length, self.layout, list(self.senses))


_last: list = []      # the last model resolved and its Drive (models are frozen)


def resolve(model) -> Drive:
    """The :class:`Drive` of ``model`` (a Drive is returned as it is). The last model's Drive is
    kept, so that a run's dynamics and its modes share one rest state (10-20 ms each)."""
    if isinstance(model, Drive):
        return model
    if _last and _last[0] is model:
        return _last[1]
    idx = tuple(tensioner.indices(model))
    given = model
    drive = Drive(model, compute_layout(model), idx, tuple(tensioner.senses(model)) if idx else ())
    if model.belt.pretension is None and model.belt.length is None:
        # the part installs the belt (part.py): its unstretched length, for every model alike
        from .part import part_length

        model = model.model_copy(update={"belt": model.belt.model_copy(update={"length": part_length(drive)})})
        drive = Drive(model, drive.layout, idx, drive.senses)
    _last[:] = [given, drive]
    return drive
