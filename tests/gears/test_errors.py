"""Bad input: one line naming the field, exit status 2; round trip of the example."""
import pytest

import drivedyn
from drivedyn.front.cli import main

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
    # the rating and helical fields
    (('life = "20000 h"', 'life = "-5 h"'), "iso.life"),
    (('life = "20000 h"', 'life = "2e6 h"'), "iso.life: must be <= 1e6 h"),
    (('lubricant_viscosity = "220 mm^2/s"', 'lubricant_viscosity = "5000 mm^2/s"'), "iso.lubricant_viscosity: must lie in 2..3200"),
    (('steel = "case-carburized"', 'steel = "mild"'), "iso.steel"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nsigma_hlim = "900 MPa"'), "give steel or sigma_hlim, not both"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nface_load_factor = 0.9'), "iso.face_load_factor: must lie in [1, 10]"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\ntransverse_load_factor = 11'), "iso.transverse_load_factor"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nmin_safety_pitting = 0'), "iso.min_safety_pitting: must be >= 1"),
    # ISO 6336-1: K_A >= 1 (0.5 raised S_H from 1.035 to 1.433 with status success)
    (('steel = "case-carburized"', 'steel = "case-carburized"\napplication_factor = 0.5'), "iso.application_factor: must lie in [1, 10]"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nflank_roughness = "-1 um"'), "iso.flank_roughness"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nmesh_misalignment = "-1 um"'), "iso.mesh_misalignment"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nroot_roughness = "-1 um"'), "iso.root_roughness"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nyield_strength = "-1 MPa"'), "iso.yield_strength"),
    (('steel = "case-carburized"', 'steel = "case-carburized"\nrating = 3'), "iso.rating"),
    (('teeth = 21', 'teeth = 21\nroot_radius = 0.8'), "gears[0].root_radius: must lie in (0, 0.6]"),
    (('teeth = 21', 'teeth = 21\nsteel = "brass"'), "gears[0].steel"),
    (('teeth = 21', 'teeth = 21\nhelix_angle = "50 deg"'), "gears[0].helix_angle"),
    (('teeth = 21', 'teeth = 21\nhand = "up"'), "gears[0].hand"),
    (('teeth = 21', 'teeth = 21\nhelix_angle = "15 deg"'), "different helix angles"),
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


def test_helical_pair_needs_opposite_hands(tmp_path, capsys):
    text = GOOD.replace('teeth = 21', 'teeth = 21\nhelix_angle = "15 deg"', 1)
    text = text.replace('teeth = 57', 'teeth = 57\nhelix_angle = "15 deg"\nhand = "left"', 1)
    text = text.replace('name = "gear3"\nteeth = 57', 'name = "gear3"\nteeth = 57\nhelix_angle = "15 deg"')
    for d in ('tip_diameter = "58.712 mm"\n', 'tip_diameter = "148.712 mm"\n'):
        text = text.replace(d, "")
    f = tmp_path / "m.toml"
    f.write_text(text)
    assert main(["check", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "meshes[1].gears" in err and "opposite hands" in err, err
