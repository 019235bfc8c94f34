"""The placement's walk (walk.py) compiled, for the solvers, which have numba loaded anyway: the
same functions, not a copy."""
from numba import njit
from numba.extending import register_jitable

from . import walk

# the helpers, called from the compiled walk, compiled with it
for _f in (walk.piece, walk.point, walk.next_end):
    register_jitable(_f)

walk_pieces = njit(cache=True)(walk.walk_pieces)
