"""JSON Schemas of the model kinds (drivedyn schema KIND): every shipped example validates, a
misspelt key is rejected, a unit string is accepted where a number is, and the schema's units are
those the loader converts to."""
from __future__ import annotations

import json
import tomllib

import jsonschema
import pytest
from typer.testing import CliRunner

import drivedyn
from drivedyn.core.analyses import KINDS
from drivedyn.front.cli import app
from drivedyn.front.schema import json_schema

EXAMPLES = {n: p for n, p in drivedyn.examples().items() if tomllib.loads(p.read_text()).get("kind") in KINDS}


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_every_example_validates(name):
    data = tomllib.loads(EXAMPLES[name].read_text())
    errors = list(jsonschema.Draft202012Validator(json_schema(data["kind"])).iter_errors(data))
    assert not errors, [(list(e.absolute_path), e.message) for e in errors]


@pytest.mark.parametrize("name, path, bad", [
    ("belt-5pk", ("belt",), "pretenshion"),
    ("belt-5pk", (), "simulaton"),
    ("gears-split-path", ("drive",), "sped"),
    ("span-t10", ("span",), "lenght"),
    ("mesh-load-l", ("load",), "torqe"),
])
def test_misspelt_key_is_rejected(name, path, bad):
    data = tomllib.loads(EXAMPLES[name].read_text())
    node = data
    for p in path:
        node = node[p]
    node[bad] = 1.0
    errors = list(jsonschema.Draft202012Validator(json_schema(data["kind"])).iter_errors(data))
    assert errors and any(bad in e.message for e in errors), [e.message for e in errors]
    with pytest.raises(drivedyn.ModelError):           # and the loader agrees
        drivedyn.loads(__import__("tomli_w").dumps(data))


def test_units_and_strings():
    s = json_schema("belt-drive")
    v = jsonschema.Draft202012Validator(s)
    data = tomllib.loads(EXAMPLES["belt-5pk"].read_text())
    data["belt"]["pretension"] = "0.55 kN"
    assert not list(v.iter_errors(data))
    data["belt"]["pretension"] = "lots"
    assert list(v.iter_errors(data))
    assert "unit" in json.dumps(s) and '"N/m^2"' in json.dumps(s)


def test_schema_command(tmp_path):
    res = CliRunner().invoke(app, ["schema", "toothed-mesh"])
    assert res.exit_code == 0 and json.loads(res.output)["properties"]["kind"]
    res = CliRunner().invoke(app, ["schema", "belt"])
    assert res.exit_code == 2 and "unknown kind" in res.output


def test_bounds_in_standard_keywords_refuse_a_negative_mass():
    """Bounds as JSON Schema states them (exclusiveMinimum, minimum, ...), not pydantic's gt / ge,
    which a validator ignores: a negative mass or radius is rejected by the schema itself."""
    schema = json_schema("belt-drive")
    text = json.dumps(schema)
    assert '"gt"' not in text and '"ge"' not in text and '"exclusiveMinimum"' in text
    data = tomllib.loads(EXAMPLES["belt-5pk"].read_text())
    data["belt"]["mass_per_length"] = -0.1
    data["pulleys"][0]["radius"] = -0.027
    bad = {tuple(e.absolute_path)[:3] for e in jsonschema.Draft202012Validator(schema).iter_errors(data)}
    assert ("belt", "mass_per_length") in {b[:2] for b in bad} and ("pulleys", 0, "radius") in bad


def test_the_reference_writes_units_as_code():
    """N*m*s/rad in the model-file reference reads as written (Markdown made "Nms/rad" with an italic m)."""
    from drivedyn.front.schema import reference_markdown

    text = reference_markdown("belt-drive")
    assert "| `N*m*s/rad` |" in text and "| N*m*s/rad |" not in text


def _properties(schema):
    """(table, field, schema node) of every property of a schema: the top level's and each $defs table's."""
    yield from (("top level", n, v) for n, v in schema.get("properties", {}).items())
    for table, node in schema.get("$defs", {}).items():
        yield from ((table, n, v) for n, v in node.get("properties", {}).items())


def _undescribed(schema):
    return [f"{t}.{n}" for t, n, v in _properties(schema) if not str(v.get("description") or "").strip()]


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_property_says_what_it_means(kind):
    """Every field of every model kind has a description in the schema (an editor shows it on hover):
    the docstring written under the field in the model class."""
    schema = json_schema(kind)
    assert len(list(_properties(schema))) > 20
    assert not _undescribed(schema)


def test_every_study_field_says_what_it_means():
    from drivedyn.front.schema import spec_json_schema
    from drivedyn.study.spec import StudySpec

    assert not _undescribed(spec_json_schema(StudySpec))


def test_descriptions_carry_the_unit_and_reach_the_reference():
    """A physical field's description ends with its SI unit (editors ignore the ``unit`` keyword), and the
    model-file reference of the docs prints each field's description in its "meaning" column."""
    from drivedyn.front.schema import reference_markdown

    belt = json_schema("belt-drive")["$defs"]["Belt"]["properties"]
    assert belt["pretension"]["description"].startswith("Installation (static) tension")
    assert belt["pretension"]["description"].endswith("(SI unit: N; a string with a unit is converted)")
    assert "\n" not in belt["pretension"]["description"]
    text = reference_markdown("belt-drive")
    assert "| field | type | unit (SI) | default | bounds | meaning |" in text
    row = next(line for line in text.splitlines() if line.startswith("| `pretension` |"))
    assert row.count(" | ") == 5 and "Installation (static) tension" in row
    assert "SI unit" not in row                        # the reference has its own unit column


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_table_says_what_it_is(kind):
    """Each table of a model file has its class's docstring as its description (the reference prints it
    above the table's fields)."""
    assert not [n for n, d in json_schema(kind).get("$defs", {}).items() if not d.get("description")]
