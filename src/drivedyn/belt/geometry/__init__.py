"""The drive's geometry, shared by every fidelity: the layout on the pulleys' circles (layout.py), the
tensioners' moving geometry and static equilibrium (tensioner.py), the belt placed on its path as
segments (placement.py) and how many (segment_count.py), installation by span frequency
(installation.py). Nothing here imports the rest of the belt package but its model file."""
from ...mechanics.layout import Layout, Span, compute_layout

__all__ = ["Layout", "Span", "compute_layout"]
