"""The lean evaluation of an optimisation's designs: only the summary keys its objective and
constraints name, with the full run's numbers; when a study takes it, and its own cache key."""
import json

import drivedyn
from drivedyn.core.analyses import analysis
from drivedyn.belt.rotational.periodic import lean_keys
from drivedyn.study.cases import TOKEN, case_keys, resolve, run_case
from drivedyn.study.design import Design, overrides_of
from drivedyn.study.spec import load_study

EXAMPLE = drivedyn.example_path("study-tensioner-design")
KEYS = ["runup.arm_travel_range.tensioner", "runup.slip.*", "runup.span_tension_min.*", "runup.span_tension_max.*"]
DESIGN = {"pulleys.tensioner.arm.preload": 21.0, "pulleys.tensioner.arm.rate": 45.0,
          "pulleys.tensioner.arm.friction": 3.0, "pulleys.tensioner.arm.damping": 0.3}


def _study(write_study, extra=""):
    text = EXAMPLE.read_text().replace('base = "fead-runup.toml"',
                                       f'base = "{drivedyn.example_path("fead-runup").as_posix()}"')
    return load_study(write_study(text + extra))


def test_lean_keys():
    assert lean_keys(KEYS) == {"arm_travel_range", "slip", "span_tension_min", "span_tension_max"}
    assert lean_keys(["runup.order_peaks.span_tension.*.4.amplitude"]) == {"order_peaks"}
    for other in (["runup.*"], ["runup.slip*"], ["pulleys.alternator.slip"], ["verdict"], ["*"]):
        assert lean_keys(KEYS + other) is None


def test_lean_run_equals_the_full_run(write_study, tmp_path):
    """For one design, every key the lean run gives equals the full run's to the last bit (and its
    unit); through run_case, the record's summary too."""
    study = _study(write_study)
    labels = [p.label for p in study.spec.parameters]
    case = resolve(study, Design(labels, False, {}, [{k: DESIGN[k] for k in labels}]), overrides_of)[0]
    assert case.keys == KEYS
    model = drivedyn.loads(case.toml)
    full = drivedyn.run(model)
    lean = analysis("belt-drive").run_lean(model, KEYS)
    fs, ls = full.flat_summary(), lean.flat_summary()
    assert set(ls) < set(fs) and len(ls) > 20
    assert not [k for k in ls if ls[k] != fs[k]]
    assert all(lean.units[k] == full.units[k] for k in lean.units)
    assert not any(k.startswith("runup.order_peaks") for k in ls)        # not asked for: not computed
    assert len(lean.ds.data_vars) == 0 and "criteria" not in lean.summary
    # order peaks when asked for, equal too
    peaks = analysis("belt-drive").run_lean(model, ["runup.order_peaks.arm_travel.*"]).flat_summary()
    assert {k: v for k, v in peaks.items() if k.startswith("runup.order_peaks")} == \
        {k: v for k, v in fs.items() if k.startswith("runup.order_peaks")}
    # a worker's record of the lean case
    cache = tmp_path / "cases"
    cache.mkdir()
    (cache / TOKEN).write_text("t")
    rec = run_case(case.toml, case.key, str(cache), "t", [], None, "run", case.keys)
    assert rec["status"] == "success"
    assert rec["summary"] == json.loads(json.dumps({k: fs[k] for k in rec["summary"]}))
    assert {u for k, u in rec["units"].items() if k.startswith("runup.span_tension_min.")} == {"N"}


def test_when_a_study_runs_lean(write_study):
    study = _study(write_study)
    assert case_keys(study) == KEYS
    labels = [p.label for p in study.spec.parameters]
    design = Design(labels, False, {}, [{k: DESIGN[k] for k in labels}])
    lean = resolve(study, design, overrides_of)[0]
    # every key asked for (outputs.summary given): the full run, under the full run's cache key
    full = _study(write_study, '\n[outputs]\nsummary = ["*"]\n')
    assert case_keys(full) is None
    case = resolve(full, design, overrides_of)[0]
    assert case.keys is None and case.toml == lean.toml and case.key != lean.key
    # a key the lean run does not give: the full run
    other = _study(write_study, "").spec.optimise.model_copy(update={"objective": "pulleys.alternator.slip"})
    study.spec = study.spec.model_copy(update={"optimise": other})
    assert resolve(study, design, overrides_of)[0].keys is None
    # whole variables asked for: the full run
    assert case_keys(_study(write_study, '\n[outputs]\nseries = ["span_tension"]\n')) is None
