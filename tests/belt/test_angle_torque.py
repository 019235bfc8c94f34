"""A pulley's load torque over one turn of its own angle (``torque_angle``, belt/angle_torque.py):
turned at load time into its mean and harmonics, listed by ``drivedyn check``, refused when it
does not close over a turn, and run by the kernels as the same harmonics."""
from __future__ import annotations

import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt import angle_torque
from drivedyn.front.cli import main

# two known harmonics and a mean: T = 1.5 + 3 sin(2 theta + 0.4) + 1.2 sin(4 theta - 1.1) (N m)
MEAN, HARM = 1.5, [(2, 3.0, 0.4), (4, 1.2, -1.1)]


def _torque(theta):
    return MEAN + sum(a * math.sin(k * theta + p) for k, a, p in HARM)


def _rows(step_deg=5.0, start_deg=0.0):
    n = int(round(360 / step_deg))
    return [[math.radians(start_deg + i * step_deg), _torque(math.radians(start_deg + i * step_deg))]
            for i in range(n + 1)]


@pytest.mark.parametrize("start", [0.0, -90.0])
def test_two_harmonics_reproduced(start):
    """A table sampled every 5 deg from two harmonics gives them back, amplitude and phase within
    1e-9 (the discrete Fourier transform of uniform samples is exact below half the sample count:
    Oppenheim & Schafer, sec. 8.1), and no other order above 1e-3 of the largest; any start angle."""
    rows = _rows(start_deg=start)
    rows[-1][1] = rows[0][1]           # the same value computed at 360 deg further on: one period exactly
    mean, hs = angle_torque.series(rows)
    assert mean == pytest.approx(MEAN, abs=1e-9)
    assert [h[0] for h in hs] == [2, 4]
    for (k, a, p), (k0, a0, p0) in zip(hs, HARM):
        assert a == pytest.approx(a0, abs=1e-9)
        assert math.remainder(p - p0, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)


def test_uneven_table_is_its_linear_interpolant_series():
    """A triangle wave given by its four corners (uneven rows) has the Fourier series
    (8 A / pi^2) sum_k odd (-1)^((k-1)/2) sin(k theta) / k^2 (e.g. Kreyszig, Advanced Engineering
    Mathematics, sec. 11.1): orders 1, 3, 5 to 1e-6 of A."""
    A = 2.0
    rows = [[0.0, 0.0], [0.5 * math.pi, A], [1.5 * math.pi, -A], [2 * math.pi, 0.0]]
    mean, hs = angle_torque.series(rows)
    got = {k: (a, p) for k, a, p in hs}
    assert abs(mean) < 1e-9
    for k in (1, 3, 5):
        a, p = got[k]
        assert a == pytest.approx(8 * A / (math.pi ** 2 * k ** 2), abs=1e-6 * A)
        # sign (-1)^((k-1)/2) as a phase of 0 or pi
        assert math.cos(p) == pytest.approx((-1) ** ((k - 1) // 2), abs=1e-6)
    assert all(k % 2 == 1 for k in got)


def _text(rows):
    cells = ", ".join(f'["{math.degrees(x)!r} deg", "{y!r} N*m"]' for x, y in rows)
    good = drivedyn.example_path("belt-5pk").read_text().replace("segments = [302]", "segments = [10]")
    return good.replace('torque_speed = [["-4 rev/s", "15 N*m"], ["4 rev/s", "-15 N*m"]]',
                        'torque_speed = [["-4 rev/s", "15 N*m"], ["4 rev/s", "-15 N*m"]]\ntorque_angle = [' + cells + "]")


def _closed():
    rows = _rows()
    rows[-1][1] = rows[0][1]
    return rows


def test_check_lists_the_harmonics(tmp_path, capsys):
    f = tmp_path / "cam.toml"
    f.write_text(_text(_closed()))
    assert main(["check", str(f)]) == 0
    out = capsys.readouterr().out
    assert "driven: torque_angle (73 rows) runs as mean 1.5 N m" in out
    lines = out.splitlines()
    i = next(i for i, s in enumerate(lines) if "torque_angle" in s)
    rows = [s.split() for s in lines[i + 2:i + 4]]
    assert [(int(r[0]), float(r[1]), float(r[2])) for r in rows] == [(2, 3.0, round(math.degrees(0.4), 3)),
                                                                      (4, 1.2, round(math.degrees(-1.1), 3))]


@pytest.mark.parametrize("edit, words", [
    ("torque", ["pulleys[1].torque_angle", "does not close", "(2 N*m) differs", "at 0 deg"]),
    ("angle", ["pulleys[1].torque_angle", "span one turn", "350 deg"]),
])
def test_a_table_that_does_not_close_is_refused(tmp_path, capsys, edit, words):
    rows = _closed()
    if edit == "torque":
        rows[-1][1] = 2.0
    else:
        rows = [[x * 350 / 360, y] for x, y in rows]
    f = tmp_path / "m.toml"
    f.write_text(_text(rows))
    assert main(["check", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    for w in words:
        assert w in err, err


def test_the_kernels_run_the_table_as_its_harmonics():
    """A rotational run with the table equals, to round-off, the same run with its harmonics and mean
    written out (the kernels are unchanged: the table reaches them as harmonics)."""
    base = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                            {"simulation.model": "rotational", "simulation.duration": 0.1})
    table = drivedyn.replace(base, {"pulleys.driven.torque_angle": _closed()})
    assert drivedyn.loads(drivedyn.dumps(table)) == table           # the file round trip keeps the table
    mean, hs = angle_torque.series(_closed())
    written = drivedyn.replace(base, {"pulleys.driven.torque": mean,
                                      "pulleys.driven.harmonics": [{"order": k, "amplitude": a, "phase": p} for k, a, p in hs]})
    a, b = drivedyn.run(table).ds, drivedyn.run(written).ds
    assert np.allclose(a["speed"].values, b["speed"].values, rtol=1e-12, atol=1e-12)
    assert not np.allclose(a["speed"].values, drivedyn.run(base).ds["speed"].values, rtol=1e-6)
