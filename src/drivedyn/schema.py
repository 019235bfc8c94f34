"""JSON Schema of each model kind (``drivedyn schema KIND``), from the pydantic models themselves,
so that editors (Taplo / Even Better TOML) complete and check model files, and the model-file
reference of the documentation (docs/hooks.py) is generated from the same source.

A physical field (``drivedyn.model.quantity``) accepts a number in SI units or a string with a
unit ("27 mm"): its schema says so (``anyOf`` number / string) and carries its SI ``unit``; the
numeric bounds apply to numbers (a string is converted and checked at load time).
"""
from __future__ import annotations

import copy

from .analyses import analysis

#: a number followed by a unit, as drivedyn.units reads it ("27 mm", "1450 rpm", "-15 N*m", "2e5 N")
UNIT_STRING = r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*\S.*$"


def _with_units(node):
    if isinstance(node, dict):
        node = {k: _with_units(v) for k, v in node.items()}
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


def json_schema(kind: str) -> dict:
    """The JSON Schema (draft 2020-12) of a model file of ``kind``."""
    model = analysis(kind).Model
    s = copy.deepcopy(model.model_json_schema(mode="validation"))
    s = _with_units(s)
    s["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    s["title"] = f"drivedyn model file, kind = \"{kind}\""
    return s
