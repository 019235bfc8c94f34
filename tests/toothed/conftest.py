"""Shared helpers of the toothed-mesh tests."""
import numpy as np
import pytest

from drivedyn.mechanics.teeth import catalogue
from drivedyn.toothed.engagement import sweep
from drivedyn.mechanics.teeth.pair import build


def make_pair(belt, pulley=None, z=24, groove="standard", offset=0.0, tol=5e-7, spacing=2e-5):
    """A catalogue pair (all lengths SI)."""
    return build(catalogue.tooth(belt), pulley or belt, None, z, groove, None, 0.0, offset, tol, spacing)


@pytest.fixture(scope="session")
def htd_sweep():
    """HTD 8M on 24 teeth, 121 angles (shared: several tests read it)."""
    return sweep(make_pair("HTD8M"), 121)


MM = 1e-3
DEG = np.pi / 180
