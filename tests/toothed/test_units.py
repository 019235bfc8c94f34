"""The toothed summary carries units (its keys end in their unit)."""
import drivedyn


def test_toothed_units():
    r = drivedyn.run(drivedyn.load(drivedyn.example_path("mesh-l")))
    assert r.units["max_penetration_mm"] == "mm" and r.units["geometry.first_contact_deg"] == "deg"
