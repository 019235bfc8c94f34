"""End to end: run a seed example, save, plot, and read it back."""
import json

import drivedyn
from drivedyn.core.results import open_result


def test_run_save_plot_htd8m(tmp_path):
    m = drivedyn.load(drivedyn.example_path("mesh-htd8m"))
    m = drivedyn.core.model.replace(m, {"mesh.angles": 61, "maps.teeth": [20, 32], "maps.angles": 21})
    r = drivedyn.run(m)
    r.save(tmp_path)
    doc = json.loads((tmp_path / "summary.json").read_text())
    for key in ("max_overlap_area_mm2", "max_penetration_mm"):
        assert doc[key] > 0
    assert doc["flanks"]["leading"]["max_penetration_mm"] > 0
    assert doc["flanks"]["trailing"]["max_penetration_mm"] > 0
    assert len(doc["comparison"]) == 5
    from drivedyn import api

    files = api.plot(open_result(tmp_path), tmp_path)
    names = {f.name for f in files}
    assert {"mesh-contours.png", "mesh-interference.png", "mesh-flank-map.png", "mesh-maps.png",
            "mesh-comparison.png", "mesh-animation.gif"} <= names
    assert all(f.stat().st_size > 1000 for f in files)
    # the animation: the pulley drawn once, the tooth moving over it, the angle changing above it
    from PIL import Image, ImageChops

    gif = Image.open(tmp_path / "mesh-animation.gif")
    assert gif.n_frames == 48
    gif.seek(0)
    first = gif.convert("RGB")
    gif.seek(47)
    last = gif.convert("RGB")
    w, h = first.size
    moved = ImageChops.difference(first, last)
    assert moved.crop((0, h // 10, w, h)).getbbox() is not None        # the tooth
    assert moved.crop((0, 0, w, h // 10)).getbbox() is not None        # the angle in the title
    report = drivedyn.check(m)
    assert "pitch error" in report and "tip clearance 0.071" in report
