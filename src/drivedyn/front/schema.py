"""JSON Schema of each model kind (``drivedyn schema KIND``), from the pydantic models themselves,
so that editors (Taplo / Even Better TOML) complete and check model files, and the model-file
reference of the documentation (docs/hooks.py) is generated from the same source.

A physical field (``drivedyn.core.model.quantity``) accepts a number in SI units or a string with a
unit ("27 mm"): its schema says so (``anyOf`` number / string) and carries its SI ``unit``; the
numeric bounds apply to numbers (a string is converted and checked at load time).
"""
from __future__ import annotations

import copy

from ..core.analyses import analysis

#: a number followed by a unit, as drivedyn.core.units reads it ("27 mm", "1450 rpm", "-15 N*m", "2e5 N")
UNIT_STRING = r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*\S.*$"


#: pydantic's bound names, where they stand in a number's schema, and JSON Schema's (draft 2020-12)
BOUNDS = {"gt": "exclusiveMinimum", "ge": "minimum", "lt": "exclusiveMaximum", "le": "maximum"}


def _with_units(node):
    if isinstance(node, dict):
        node = {k: _with_units(v) for k, v in node.items()}
        if node.get("type") in ("number", "integer"):
            # a validator and an editor read the standard keywords (they passed a negative mass)
            node = {BOUNDS.get(k, k): v for k, v in node.items()}
        if "unit" in node and node.get("type") in ("number", "integer"):
            num = {k: v for k, v in node.items() if k not in ("unit", "title", "description", "default")}
            rest = {k: v for k, v in node.items() if k in ("unit", "title", "description", "default")}
            node = {**rest, "anyOf": [num, {"type": "string", "pattern": UNIT_STRING}]}
        elif "unit" in node and "anyOf" in node:
            alts = []
            for a in node["anyOf"]:
                if isinstance(a, dict) and a.get("type") in ("number", "integer"):
                    alts += [a, {"type": "string", "pattern": UNIT_STRING}]
                else:
                    alts.append(a)
            node["anyOf"] = alts
        return node
    if isinstance(node, list):
        return [_with_units(v) for v in node]
    return node


def _units_in(node) -> set:
    """The SI units a property's schema declares, down through anyOf / prefixItems / items (not $ref)."""
    if isinstance(node, list):
        return set().union(*(_units_in(v) for v in node)) if node else set()
    if not isinstance(node, dict):
        return set()
    found = {node["unit"]} if isinstance(node.get("unit"), str) and node["unit"] else set()
    for k in ("anyOf", "prefixItems", "items", "additionalProperties"):
        if k in node:
            found |= _units_in(node[k])
    return found


def _unit_in_descriptions(schema: dict) -> dict:
    """Each property's description ends with its SI unit, where it has one ("(SI unit: N)"): an editor
    shows the description on hover and ignores the non-standard ``unit`` keyword."""
    tables = [schema] + list(schema.get("$defs", {}).values())
    for t in tables:
        for node in t.get("properties", {}).values():
            if node.get("description"):       # docstrings wrap at the code's width: one line for a tooltip
                node["description"] = " ".join(node["description"].split())
            units = _units_in(node)
            if len(units) == 1 and node.get("description") and "(SI unit:" not in node["description"]:
                u = units.pop()
                if u != "1":
                    node["description"] += f" (SI unit: {u}; a string with a unit is converted)"
    return schema


def _described():
    """pydantic's schema generator with each model field's docstring (drivedyn.core.model.field_docs) as
    the description of its property."""
    from pydantic.json_schema import GenerateJsonSchema

    from ..core.model import field_docs

    class Described(GenerateJsonSchema):
        def model_schema(self, schema):
            out = super().model_schema(schema)
            props = self.resolve_ref_schema(out).get("properties", {})
            for name, text in field_docs(schema["cls"]).items():
                if name in props and not props[name].get("description"):
                    props[name]["description"] = text
            return out

    return Described


def spec_json_schema(cls) -> dict:
    """The JSON Schema of a model class (a model kind's ``Model``, a study's ``StudySpec``): bounds in
    JSON Schema's keywords, unit strings accepted where numbers are, and every property's
    description the docstring under its field, on one line and ending with its SI unit."""
    s = copy.deepcopy(cls.model_json_schema(mode="validation", schema_generator=_described()))
    return _unit_in_descriptions(_with_units(s))


def json_schema(kind: str) -> dict:
    """The JSON Schema (draft 2020-12) of a model file of ``kind``."""
    s = spec_json_schema(analysis(kind).Model)
    s["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    s["title"] = f"drivedyn model file, kind = \"{kind}\""
    return s


def _type_text(ann) -> str:
    import typing

    from pydantic import BaseModel

    from ..core.model import unwrap

    core, _ = unwrap(ann)
    origin = typing.get_origin(core)
    if isinstance(core, type) and issubclass(core, BaseModel):
        return f"table [{core.__name__}](#{core.__name__.lower()})"
    if origin in (list, tuple):
        args = [a for a in typing.get_args(core) if a is not Ellipsis]
        inner = ", ".join(dict.fromkeys(_type_text(a) for a in args)) or "any"
        return f"list of {inner}" if origin is list else f"[{inner}]"
    if origin is typing.Literal:
        return " / ".join(f'`"{a}"`' if isinstance(a, str) else f"`{a}`" for a in typing.get_args(core))
    if origin in (typing.Union,) or str(origin) == "<class 'types.UnionType'>":
        return " or ".join(_type_text(a) for a in typing.get_args(core) if a is not type(None))
    if core is list:
        return "row [x, y] (numbers or strings with units)"
    return {float: "number", int: "integer", str: "string", bool: "true / false"}.get(core, str(core).replace("typing.", ""))


def _cell(text: str) -> str:
    """A description as one Markdown table cell: one line, pipes escaped, the asterisks of units
    (N*m) not read as emphasis, the angle brackets of "<= 0" not as HTML."""
    return " ".join(text.split()).replace("|", "\\|").replace("*", "\\*").replace("<", "&lt;")


def reference_markdown(kind: str) -> str:
    """The model-file reference of ``kind`` as Markdown tables, one per table of the file, from
    the pydantic models (field, type, SI unit, default, bounds) and their docstrings (the class's
    above its table, each field's in the table's "meaning" column)."""
    import inspect
    import typing

    from pydantic import BaseModel
    from pydantic_core import PydanticUndefined

    from ..core.model import field_docs, unwrap

    root = analysis(kind).Model
    seen, order = set(), []

    def collect(cls):
        if cls in seen:
            return
        seen.add(cls)
        order.append(cls)
        for f in cls.model_fields.values():
            stack = [f.annotation]
            while stack:
                a = stack.pop()
                core, _ = unwrap(a)
                if isinstance(core, type) and issubclass(core, BaseModel):
                    collect(core)
                else:
                    stack += [x for x in typing.get_args(core) if x is not Ellipsis and x is not type(None)]

    collect(root)
    out = []
    for cls in order:
        name = "top level" if cls is root else cls.__name__
        out.append(f"## {name}" if cls is root else f"## {cls.__name__}")
        doc = inspect.getdoc(cls) or ""
        if doc and not doc.startswith(("Base", "A base")):
            out += ["", doc.split("\n\n")[0].replace("\n", " ")]
        out += ["", "| field | type | unit (SI) | default | bounds | meaning |", "|---|---|---|---|---|---|"]
        docs = field_docs(cls)
        for fname, f in cls.model_fields.items():
            unit = ""
            for m in f.metadata:
                e = getattr(m, "json_schema_extra", None)
                if isinstance(e, dict) and e.get("unit"):
                    unit = e["unit"]
            if not unit and isinstance(f.json_schema_extra, dict):
                unit = f.json_schema_extra.get("unit", "")
            unit = unit or (unwrap(f.annotation)[1] or "")
            if not unit:        # a tuple whose items carry one unit (a centre: (m, m)), a table's columns
                items = {unwrap(a)[1] for a in typing.get_args(unwrap(f.annotation)[0]) if a is not Ellipsis}
                unit = items.pop() or "" if len(items) == 1 else ""
            if not unit:
                from .report import TABLE_UNITS

                unit = TABLE_UNITS.get(fname, "")
            if f.is_required():
                default = "**required**"
            elif f.default is None:
                default = "none"
            elif f.default is PydanticUndefined:
                default = "(the table's defaults)" if f.default_factory is not None else ""
            elif isinstance(f.default, BaseModel):
                default = "(the table's defaults)"
            else:
                default = f"`{f.default!r}`".replace("|", "\\|")
            bounds = []
            for m in f.metadata:
                for attr, sym in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
                    v = getattr(m, attr, None)
                    if v is not None:
                        bounds.append(f"{sym} {v:g}")
            t = _type_text(f.annotation)
            if unit and t.startswith("number"):
                t = "number or string with unit"
            # a unit in code: Markdown read N*m*s/rad as N, an italic m, s/rad
            meaning = _cell(docs.get(fname) or f.description or "")
            out.append(f"| `{fname}` | {t} | {f'`{unit}`' if unit else ''} | {default} | {', '.join(bounds)} | {meaning} |")
        out.append("")
    return "\n".join(out)
