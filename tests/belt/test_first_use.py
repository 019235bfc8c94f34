"""A run's first use of the segment model's kernels: each scheme compiles its own stages only, the
progress line says while numba compiles, and rkf45 refuses at once a friction law it cannot step
through within an output interval."""
import re

import pytest
from numba import njit

import drivedyn
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments import system
from drivedyn.belt.segments.state import new_state, new_work


def _stages_compiled_in(model):
    """The kernel stages the time loop of ``model``'s scheme links, from a copy of ``_advance``
    compiled afresh (not from numba's cache; the stages themselves may come from it)."""
    sysm = system.build(model)
    B, C, P, A = sysm.groups
    S = new_state(sysm)
    W = new_work(sysm, S)
    args = (1, 0.0, sysm.step, B, C, P, A, S, W, *K.scheme(B), K.scratch(B, P))
    fresh = njit(_nrt=False, error_model="numpy", no_cpython_wrapper=True, no_cfunc_wrapper=True)(K._advance.py_func)
    fresh.compile(tuple(fresh.typeof_pyval(a) for a in args))
    ir = next(iter(fresh.overloads.values())).library.get_llvm_str()
    return {name for name in ("_contacts_semi", "_base_solve", "_check", "_refactor") if re.search(rf"\d{name}B", ir)}


@pytest.mark.parametrize("method, stages", [("semi-implicit", {"_contacts_semi"}),
                                            ("implicit", {"_base_solve", "_check", "_refactor"})])
def test_each_scheme_compiles_its_own_stages_only(model_factory, method, stages):
    # (the implicit kernel compiled the semi-implicit scheme's contact stage too: 48 s of a first
    # run's compile instead of 21)
    assert _stages_compiled_in(model_factory(simulation__method=method, belt__segments=60)) == stages


def test_rkf45_first_use_says_it_compiles(model_factory, monkeypatch):
    # a copy of the kernel outside numba's cache: its first use compiles, as from an empty cache
    monkeypatch.setattr(K, "rkf45_chunk", njit(no_cfunc_wrapper=True)(K.rkf45_chunk.py_func))
    m = model_factory(simulation__method="rkf45", friction__velocity_threshold=5e-2, simulation__duration=2e-3,
                      belt__segments=60)
    said = []
    drivedyn.run(m, progress=lambda frac, text: said.append((frac, text)))
    assert said[0] == (0.0, "compiling the rkf45 kernels (first use, about 7 s)")
    assert not any("compiling" in text for _, text in said[1:])
    # and once compiled, not again
    said.clear()
    drivedyn.run(m, progress=lambda frac, text: said.append((frac, text)))
    assert said and not any("compiling" in text for _, text in said)


def test_rkf45_refuses_a_friction_law_too_stiff_for_an_output_interval(model_factory):
    # the seed's velocity_threshold, 1e-5 m/s: an explicit step of about 1e-10 s, 7e6 of them per
    # millisecond; it used to run for minutes at 0 % and then stop with "step size collapsed"
    m = model_factory(simulation__method="rkf45", simulation__duration=0.05)
    with pytest.raises(drivedyn.ModelError, match=r"rkf45 is explicit: .* per output interval of 0\.001 s, more "
                                                  r"than the 2e\+06 it takes before it gives up") as info:
        drivedyn.run(m)
    assert info.value.field == "simulation.method"
