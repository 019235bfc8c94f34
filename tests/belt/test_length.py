"""The belt's installed length and pretension mean the continuum's quantities, at any resolution:
a catalogue length gives creep theory's tension at rest (creep.tensions: the length balance with
the belt's depth in the grooves) whatever the segment count; a pretension is what the discrete
belt settles to at rest (its mean element force after the static equilibrium)."""
import numpy as np
import pytest

import drivedyn
from drivedyn.mechanics.layout import compute_layout
from drivedyn.belt.steady.creep import drive_of, tensions
from drivedyn.belt.segments.system import build, settled_tension


def _5pk(**over):
    return drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")), {"output.segments": [0], **over})


@pytest.mark.parametrize("n", [75, 150, 300, 600])
def test_pretension_is_the_settled_tension(n):
    sysm = build(_5pk(**{"belt.segments": n}))
    assert settled_tension(sysm) == pytest.approx(550.0, rel=3e-3)
    assert sysm.init.tension == pytest.approx(settled_tension(sysm), rel=1e-12)


def test_catalogue_length_gives_the_same_tension_at_any_segment_count():
    base = _5pk()
    # a length that holds about 450 N on the drawn path (a catalogue length would be rounded)
    length = round(compute_layout(base).length / (1 + 450.0 / base.belt.axial_stiffness), 4)
    m = _5pk(**{"belt.pretension": None, "belt.length": length})
    T_cont = float(np.mean(tensions(drive_of(m), np.zeros(2), 0.0, True)))
    assert 300 < T_cont < 800                                  # a taut belt, not a slack or absurd one
    got = [settled_tension(build(drivedyn.replace(m, {"belt.segments": n}))) for n in (150, 300, 600)]
    np.testing.assert_allclose(got, T_cont, rtol=3e-3)
    # and the contact stiffness changes it only through the belt's depth in the grooves, as in the continuum
    soft = drivedyn.replace(m, {"contact.stiffness_linear": 0.5 * m.contact.stiffness_linear})
    T_soft = float(np.mean(tensions(drive_of(soft), np.zeros(2), 0.0, True)))
    assert settled_tension(build(soft)) == pytest.approx(T_soft, rel=3e-3)
