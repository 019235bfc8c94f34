"""Bad input: one line naming the field, exit status 2; round trip of the example."""
import pytest

import drivedyn
from drivedyn.cli import main

GOOD = drivedyn.example_path("gears-split-path").read_text()


@pytest.mark.parametrize("edit, expect", [
    (("teeth = 21", "teeth = 4"), "gears[0].teeth: must be >= 5"),
    (('face_width = "26 mm"', 'face_width = "-26 mm"'), "gears[0].face_width"),
    (('gears = ["pinion", "gear3"]', 'gears = ["pinion", "gear4"]'), "meshes[1].gears: no gear named 'gear4'"),
    (('gears = ["pinion", "gear3"]', 'gears = ["gear2", "gear2"]'), "meshes"),
    (('tip_diameter = "148.712 mm"', 'tip_diameter = "144 mm"'), "meshes[0]: contact ratio"),
    (('module = "2.5 mm"\npressure_angle = "20 deg"\nprofile_shift = 0.29\nface_width = "24 mm"',
      'module = "3 mm"\npressure_angle = "20 deg"\nprofile_shift = 0.29\nface_width = "24 mm"'), "different modules"),
    (('position_angle = "0 deg"', 'position_angle = "0 deg"\nfrcition = 0.1'), "did you mean 'friction'"),
    (('power = "7.5 kW"', ''), "drive"),
])
def test_bad_input_one_line_exit_2(tmp_path, capsys, edit, expect):
    old, new = edit
    assert old in GOOD
    f = tmp_path / "m.toml"
    f.write_text(GOOD.replace(old, new, 1))
    code = main(["check", str(f)])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1, err
    assert expect in err, err


def test_disconnected_gear(tmp_path, capsys):
    text = GOOD.replace('gears = ["pinion", "gear3"]', 'gears = ["pinion", "gear2"]')
    f = tmp_path / "m.toml"
    f.write_text(text)
    assert main(["check", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert "meshes" in err and "not connected" in err and "gear3" in err


def test_roundtrip_of_example():
    m = drivedyn.load(drivedyn.example_path("gears-split-path"))
    assert drivedyn.loads(drivedyn.dumps(m)) == m


def test_check_prints_geometry_stiffness_and_frequencies():
    text = drivedyn.check(drivedyn.example_path("gears-split-path"))
    import math

    rb1, rb2 = 0.02625 * math.cos(math.radians(20)), 0.07125 * math.cos(math.radians(20))
    m1, m2, k = 1.47e-4 / rb1 ** 2, 7.81e-3 / rb2 ** 2, 449.9e6
    # split path, closed forms: anti-phase mode (pinion still) and in-phase mode
    f_anti = math.sqrt(k / m2) / (2 * math.pi)
    f_in = math.sqrt(k * (1 / m2 + 2 / m1)) / (2 * math.pi)
    for key in ("contact ratio eps_alpha 1.5001", "c_gamma_alpha", "natural frequencies",
                f"{f_anti:10.2f} Hz", f"{f_in:10.2f} Hz"):
        assert key in text, key
