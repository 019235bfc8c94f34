"""A run's first use of the segment model's kernels: each scheme compiles its own stages only, the
progress line says while numba compiles, and rkf45 refuses at once a friction law it cannot step
through within an output interval."""
import importlib
import os
import re
import subprocess
import sys

import pytest
from numba import njit, types
from numba.core.registry import CPUDispatcher as Dispatcher

import drivedyn
from drivedyn.belt.dynamics._bodies import State, Work
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments import ahead, simulate, system, tail
from drivedyn.belt.segments.state import new_state, new_work

_FRESH = {}     # the fresh loops compiled in this session, by argument types (5-13 s each)


def _fresh_loop(model):
    """A copy of ``_advance`` compiled afresh for ``model`` (not from numba's cache; the stages
    themselves may come from it): its compile result and its arguments. Compiled once per argument
    types in a session: the compile result depends on nothing else."""
    sysm = system.build(model)
    B, C, P, A = sysm.groups
    S = new_state(sysm)
    W = new_work(sysm, S)
    args = (1, 0.0, sysm.step, B, C, P, A, S, W, *K.scheme(B), K.scratch(B, P))
    sig = tuple(K._advance.typeof_pyval(a) for a in args)
    if sig not in _FRESH:
        fresh = njit(_nrt=False, error_model="numpy", no_cpython_wrapper=True, no_cfunc_wrapper=True)(K._advance.py_func)
        fresh.compile(sig)
        _FRESH[sig] = next(iter(fresh.overloads.values()))
    return _FRESH[sig], args


def _stages_compiled_in(model):
    """The kernel stages the time loop of ``model``'s scheme links."""
    ir = _fresh_loop(model)[0].library.get_llvm_str()
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
    assert said[0] == (0.0, "compiling the rkf45 kernels (first use: 7-30 s)")
    assert not any("compiling" in text for _, text in said[1:])
    # and once compiled, not again
    said.clear()
    drivedyn.run(m, progress=lambda frac, text: said.append((frac, text)))
    assert said and not any("compiling" in text for _, text in said)


def test_rkf45_refuses_a_friction_law_too_stiff_for_an_output_interval(model_factory, monkeypatch):
    # the seed's velocity_threshold, 1e-5 m/s: an explicit step of about 1e-10 s, 7e6 of them per
    # millisecond; it used to run for minutes at 0 % and then stop with "step size collapsed"
    # (its segment evaluations are refused first by default: lifted, the per-interval refusal holds)
    monkeypatch.setenv("DRIVEDYN_MAX_EVALUATIONS", "inf")
    m = model_factory(simulation__method="rkf45", simulation__duration=0.005)   # (0.05 s: over the steps limit first)
    with pytest.raises(drivedyn.ModelError, match=r"rkf45 is explicit: .* per output interval of 0\.001 s, more "
                                                  r"than the 2e\+06 it takes before it gives up") as info:
        drivedyn.run(m)
    assert info.value.field == "simulation.method"


def test_a_run_compiles_its_time_loop_ahead_for_the_types_it_calls_it_with(model_factory, monkeypatch):
    # the second process compiles _advance while the belt settles; for other types it would be
    # compiled twice (once there, once here)
    started, used = [], []
    monkeypatch.setattr(ahead, "start", lambda module, name, args, before: started.append((module, name, args)))
    compiled = simulate.compiled
    monkeypatch.setattr(simulate, "compiled", lambda d, args: used.append(args) or compiled(d, args))
    drivedyn.run(model_factory(simulation__duration=2e-3, belt__segments=60))
    (module, name, args), = started
    assert getattr(importlib.import_module(module), name) is K._advance
    assert [K._advance.typeof_pyval(a) for a in args] == [K._advance.typeof_pyval(a) for a in used[0]]


def test_a_kernel_compiled_ahead_is_loaded_from_the_cache_not_compiled_again(tmp_path):
    code = """
from numba import types
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.belt.segments import ahead
job = ahead.start(BK.__name__, "threlfall", (0.5, 1.0))
assert job is not None and job.wait()
assert ahead.cached(BK.threlfall, (types.float64, types.float64))
assert ahead.start(BK.__name__, "threlfall", (0.5, 1.0)) is None      # nothing left to do
assert BK.threlfall(0.5, 1.0) == 0.6875
assert not BK.threlfall.stats.cache_misses, BK.threlfall.stats        # loaded, not compiled here
"""
    subprocess.run([sys.executable, "-c", code], env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}, check=True)


@pytest.mark.parametrize("method", ["implicit", "semi-implicit"])
def test_the_loops_last_stages_are_compiled_here_for_the_types_the_loop_calls_them_with(model_factory, method):
    # a first run compiles them here (tail.py) while the second process compiles the loop: for
    # other types each would compile twice (_check did, for the literal 0 the loop passed it)
    _, args = _fresh_loop(model_factory(simulation__method=method, belt__segments=60))
    jobs = tail.head(args[2], *args[3:9], args[-1]) + tail.stages(args[2], *args[3:9], args[-1])
    assert len(jobs) == (18 if method == "implicit" else 4)
    for stage, a in jobs:
        assert stage.signatures == [tail.signature(stage, a)], stage.py_func.__name__


def test_the_loop_passes_its_stages_arrays_not_the_state_and_work_records(model_factory):
    # the pulleys' stage, the accumulators and the energy took the records whole: 839, 500 and
    # 670 arguments once flattened, which LLVM's passes over the loop paid for
    cres, _ = _fresh_loop(model_factory(belt__segments=60))
    flat = {}
    for stage in (K._pulleys_stage, K._accumulate, K._energy):
        (sig,) = stage.signatures
        assert not any(getattr(t, "instance_class", None) in (State, Work) for t in sig)
        flat[stage.py_func.__name__] = len(K._advance.targetctx.get_arg_packer(sig).argument_types)
    assert flat["_step_pulleys_on"] < 400 and flat["_accumulate"] < 200 and flat["_energy"] < 320, flat
    # and the loop keeps no array of the records in a local name (a stack slot each, which LLVM's
    # SROA split: 1.3 s of its compile)
    # (numba's names: "x.1" another version of x, "$..." a temporary, "f_v3_..." one of an inlined f's)
    arrays = {v for v, t in cres.type_annotation.typemap.items()
              if isinstance(t, types.Array) and not any(c in v for c in "$.") and not re.search(r"_v\d+_", v)}
    assert arrays <= {"hubx", "huby", "a", "b"}, sorted(arrays)     # (a, b: the scratch zeroed)


def test_energy_and_the_static_forces_compile_once_for_python_and_the_loop(model_factory):
    # called from Python through their arrays: the records' wrappers (energy 4.5 s of a first run's
    # compile, static_forces 3.7 s) are gone, and the loop reuses the same compiled stage
    drivedyn.run(model_factory(simulation__duration=2e-3, belt__segments=60))
    assert len(K._energy.signatures) == 1
    assert len(K._joint_forces.signatures) == 1
    assert not isinstance(K.energy, Dispatcher) and not isinstance(K.static_forces, Dispatcher)


def test_the_two_processes_compile_each_stage_once(tmp_path):
    # the second process from the first stage on, this one from the last back, each claiming a
    # stage before it compiles it: they met on the cache alone, and both compiled the stage the
    # other had under way (_joint_forces and _join of the 5PK drive, 1 s each)
    code = """
import os
from numba import types
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.belt.segments import tail
claims = os.environ["CLAIMS"]
jobs = [(BK.smoothstep, (0.5,)), (BK.threlfall, (0.5, 1.0))]
assert tail.claim(claims, BK.threlfall) and not tail.claim(claims, BK.threlfall)
assert tail.compile_back(jobs, lambda: True, claims) == []            # the last one taken: met there
assert tail.claim(None, BK.threlfall)                                 # no second process: all ours
args = (1, 0.0, 1e-5, None, None, None, None, None, None, None, None, None)
tail.head = lambda h, B, Ct, P, A, S, W, X: jobs[:1]
tail.stages = lambda h, B, Ct, P, A, S, W, X: jobs[1:]
# forward: smoothstep compiled, threlfall claimed by the other: waits for it in the cache
assert tail.compile_forward(args, claims, patience=0.2) == ["smoothstep"]
assert not BK.threlfall.signatures
# the other gives a stage back (its compile failed): the wait ends at once, the loop compiles it
import time
os.remove(os.path.join(claims, "threlfall"))
t = time.monotonic()
assert tail.compile_forward(args, claims, patience=30.0) == ["threlfall"]
assert time.monotonic() - t < 10.0
"""
    (tmp_path / "claims").mkdir()
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache"), "CLAIMS": str(tmp_path / "claims")}
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    assert sorted(p.name for p in (tmp_path / "claims").iterdir()) == ["smoothstep", "threlfall"]


def test_a_stage_this_process_fails_to_compile_is_given_back(tmp_path, monkeypatch):
    from drivedyn.belt.dynamics import _bodies as BK

    def fail(sig):
        raise RuntimeError("numba moved")

    monkeypatch.setattr(BK.threlfall, "compile", fail)
    monkeypatch.setattr(tail, "cached", lambda stage, sig: False)
    claims = str(tmp_path)
    assert tail.compile_back([(BK.threlfall, (0.5, 1.0))], lambda: True, claims) == []
    assert not os.listdir(claims)         # its claim removed: the second process does not wait on it


def test_stages_compile_from_the_last_back_until_one_is_cached(tmp_path):
    code = """
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.belt.segments import tail
jobs = [(BK.smoothstep, (0.5,)), (BK.threlfall, (0.5, 1.0))]
assert tail.compile_back(jobs, lambda: False) == []                  # the second process is done
assert tail.compile_back(jobs[1:], lambda: True) == ["threlfall"]
assert tail.compile_back(jobs, lambda: True) == []                   # threlfall cached: met there
BK.threlfall.overloads.clear()
assert tail.compile_back(jobs[:1], lambda: True) == ["smoothstep"]
"""
    subprocess.run([sys.executable, "-c", code], env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}, check=True)
