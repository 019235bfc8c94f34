"""Meta-tests over every analysis: the shared contract (load, run twice in one process, save,
reopen, plot, check, round-trip of the model file)."""
import pytest

import drivedyn
from drivedyn.core.model import KINDS

# the cheapest shipped example of each kind, shortened where the kind allows it
CASES = {
    "belt-drive": ("belt-verification", {"simulation.duration": 0.02, "output.frames": 2}),
    "gear-train": ("gears-split-path", {"sweep.enabled": False}),
    "span-stability": ("span-t10", {}),
    "toothed-mesh": ("mesh-l", {}),
}


def test_every_kind_has_a_case():
    assert set(CASES) == set(KINDS)


@pytest.mark.parametrize("kind", sorted(CASES))
def test_contract(kind, tmp_path):
    name, overrides = CASES[kind]
    model = drivedyn.replace(drivedyn.load(drivedyn.example_path(name)), overrides) if overrides else \
        drivedyn.load(drivedyn.example_path(name))
    assert model.kind == kind
    assert drivedyn.loads(drivedyn.dumps(model)) == model
    assert isinstance(drivedyn.check(model), str)
    first = drivedyn.run(model)
    second = drivedyn.run(model)                  # twice in one process (as a study worker does)
    assert first.success and second.success
    assert first.flat_summary().keys() == second.flat_summary().keys()
    first.save(tmp_path)
    back = drivedyn.open_result(tmp_path)
    assert back.kind == kind and back.status == first.status
    assert back.summary.keys() == first.summary_document().keys() - {"kind", "status", "message", "diagnostics", "units"}
    assert back.diagnostics == first.diagnostics and back.units == first.units
    assert drivedyn.api.plot(back, tmp_path / "plots")
