"""The belt is the part (belt/geometry/part.py): a belt named by its effective length installs the
drive for check, the supplier's tables and both dynamic models alike; the tensioner sits where the
required belt length is the part's (positions.py's "installed" row).

The drive is examples/fead-ag0868.toml (the Gates AG0868 report's layout and tensioner, kaydgn/MFSim
tests/fixtures/fead-validation.js, AG_MISC["AG0868"]): its position table is the report's within
0.3 % (tests/belt/test_supplier_report.py), so a belt length's tension from that table is the
supplier's own number for it.
"""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.geometry.drive import resolve
from drivedyn.belt.geometry.positions import position_tables


def _example(**changes):
    return drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-ag0868")),
                            {"duty_cycle.dynamic": False, "duty_cycle.tolerance": False, **changes})


def test_a_belt_length_study_moves_the_runs_tensions_as_the_tensioner_says():
    """Three belt lengths (1015, 1020, 1025 mm): the rotational model's span tensions (less m v^2, the
    A/C unloaded) follow the position table's tension at each length within 1 % (was: the run held
    belt.pretension whatever the length, 356 N at all three)."""
    base = _example(**{"simulation.model": "rotational", "simulation.duration": 0.5, "pulleys.1.viscous_torque": 0.0,
                       "duty_cycle": None})
    seen = []
    for L in (1.015, 1.020, 1.025):
        model = drivedyn.replace(base, {"belt.effective_length": L})
        table = position_tables(resolve(model))[0]
        assert table.installed.rebl == pytest.approx(L, abs=1e-9)
        r = drivedyn.run(model)
        v = 800 * math.pi / 30 * model.pulleys[0].radius
        c = model.belt.mass_per_length * v * v
        for name, span in r.summary["spans"].items():
            assert span["tension_mean"] - c == pytest.approx(table.installed.tension, rel=0.01), (L, name)
        seen.append(table.installed.tension)
    # the tensioner's rate: a longer belt, less tension (395, 354, 317 N)
    assert seen[0] > seen[1] * 1.08 and seen[1] > seen[2] * 1.08


def test_check_sweeps_the_belt_length_and_relates_its_lengths_and_tensions(tmp_path):
    """check --set belt.effective_length moves the tensioner and its tension; check prints one
    paragraph relating the lengths and tensions it prints; a drawn layout far from the belt's length
    warns with the numbers; a pretension other than the part's warns."""
    import contextlib
    import io

    from drivedyn.front.cli import main

    path = tmp_path / "m.toml"
    path.write_text(drivedyn.dumps(_example()))

    def check(*args):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = main(["check", str(path), *args])
        return code, out.getvalue()

    code, text = check()
    assert code == 0
    para = [ln for ln in text.splitlines() if ln.startswith("lengths and tensions:")]
    assert len(para) == 1 and "1020.00 mm" in para[0] and "1019.69 mm" in para[0]
    assert "warning" not in text
    code, text = check("--set", 'belt.effective_length="1030 mm"')
    assert code == 0
    assert "warning: the drawn layout needs a 1019.7 mm belt" in text and "1030.0 mm +- 5.0 mm" in text
    assert check("--set", 'belt.effective_length="1030 mm"', "--strict")[0] == 3
    installed = [ln for ln in text.splitlines() if ln.startswith("installed ")][0].split()
    assert 268.6 < float(installed[-3]) < 319.0          # T N: between the replace and max belt rows
    code, text = check("--set", 'belt.pretension="300 N"')
    assert "warning: belt.pretension 300.0 N installs the belt" in text


def test_a_belt_the_tensioner_cannot_hold_is_one_line_naming_the_field(tmp_path):
    """A belt 80 mm longer than the drawn drive: one line naming belt.effective_length, exit 2 (was:
    accepted, the run unchanged)."""
    import contextlib
    import io

    from drivedyn.front.cli import main

    path = tmp_path / "m.toml"
    path.write_text(drivedyn.dumps(_example(**{"belt.effective_length": 1.100})))
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["check", str(path)])
    lines = err.getvalue().strip().splitlines()
    assert code == 2 and len(lines) == 1 and "belt.effective_length" in lines[0] and "beyond the free arm" in lines[0]
