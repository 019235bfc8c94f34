"""Model files: TOML in, validated frozen objects out, and back.

Every analysis defines its model as a subclass of :class:`Spec` with a top-level
``kind: Literal[...]`` and ``schema_version``. Physical fields are declared with
:func:`quantity`, which accepts a number (taken in SI) or a string with a unit, converted
once here. Unknown keys are errors that suggest the nearest valid name.

    from drivedyn.model import Spec, quantity
    class Pulley(Spec):
        name: str
        radius: quantity("m", gt=0)
"""
from __future__ import annotations

import difflib
import importlib
import tomllib
from pathlib import Path
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError

from .errors import ModelError
from .units import to_si

SCHEMA_VERSION = 1

# kind -> analysis package. Each package exposes: Model (a Spec subclass), run(model, progress=None)
# -> Result, check(model) -> str, plot(result, outdir) -> list[Path].
KINDS = {
    "belt-drive": "drivedyn.belt",
    "gear-train": "drivedyn.gears",
    "span-stability": "drivedyn.span",
    "toothed-mesh": "drivedyn.toothed",
}


class Spec(BaseModel):
    """Base of every model object: frozen, unknown keys forbidden, defaults validated."""

    model_config = ConfigDict(extra="forbid", frozen=True, validate_default=True)


def _si_validator(unit: str):
    def convert(value: Any) -> Any:
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            try:
                return to_si(value, unit)
            except ModelError as exc:  # re-raised as a pydantic error so the field path is attached
                raise ValueError(str(exc)) from None
        return value

    return convert


def quantity(unit: str, **constraints):
    """A float field in SI ``unit`` that also accepts strings with units ("27 mm").

    ``constraints`` are pydantic's numeric bounds (gt, ge, lt, le).
    """
    return Annotated[float, BeforeValidator(_si_validator(unit)), Field(json_schema_extra={"unit": unit}, **constraints)]


def table_rows(value, units: tuple[str, str], field: str, min_rows: int = 1) -> list[list[float]]:
    """Validate a table of rows [x, y] (numbers or unit strings) into SI floats, x increasing.

    For pydantic validators: raises ValueError with a one-line message.
    """
    if not isinstance(value, (list, tuple)) or len(value) < min_rows:
        raise ValueError(f"{field} must be a list of at least {min_rows} [{units[0]}, {units[1]}] row(s)")
    rows = []
    for k, row in enumerate(value):
        if not isinstance(row, (list, tuple)) or len(row) != 2:
            raise ValueError(f"row {k} of {field} must have 2 values, got {row!r}")
        try:
            rows.append([to_si(row[0], units[0]), to_si(row[1], units[1])])
        except Exception as exc:
            raise ValueError(f"row {k} of {field}: {exc}") from None
    xs = [r[0] for r in rows]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise ValueError(f"{field}: first column must increase strictly")
    return rows


def check_name(v: str, forbidden: str = " ./") -> str:
    """A name used in result keys and dotted paths: non-empty, none of ``forbidden``."""
    if not v or any(c in v for c in forbidden):
        shown = ", ".join(repr(c) for c in forbidden)
        raise ValueError(f"must be a non-empty name without {shown}, got {v!r}")
    return v


def analysis(kind: str):
    """The analysis package of ``kind`` (imported lazily)."""
    if kind not in KINDS:
        close = difflib.get_close_matches(str(kind), KINDS, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else f" (one of {', '.join(KINDS)})"
        raise ModelError(f"unknown kind {kind!r}{hint}", field="kind")
    return importlib.import_module(KINDS[kind])


def _loc_str(loc) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def _walk(model_cls, loc):
    """(model class reached, last field) following ``loc`` through nested models (lists skipped)."""
    import typing

    cls, field = model_cls, None
    for part in loc:
        if isinstance(part, int) or cls is None:
            continue
        field = getattr(cls, "model_fields", {}).get(part)
        if field is None:
            return None, None
        cls = None
        for cand in [field.annotation, *typing.get_args(field.annotation)]:
            for c in [cand, *typing.get_args(cand)]:
                if isinstance(c, type) and issubclass(c, BaseModel):
                    cls = c
    return cls, field


def _field_unit(model_cls, loc) -> str:
    """SI unit declared (``quantity``) by the field at ``loc``, or ""."""
    import typing

    _, field = _walk(model_cls, loc)
    if field is None:
        return ""
    extras = [field.json_schema_extra] + [getattr(m, "json_schema_extra", None) for m in field.metadata]
    for a in typing.get_args(field.annotation):  # Optional[quantity(...)]: the unit sits in the Annotated
        extras += [getattr(m, "json_schema_extra", None) for m in getattr(a, "__metadata__", ())]
    for e in extras:
        if isinstance(e, dict) and e.get("unit"):
            return e["unit"]
    return ""


def _fields_at(model_cls, loc):
    """Field names of the model class reached by following ``loc`` (for suggestions)."""
    cls, _ = _walk(model_cls, loc)
    return list(getattr(cls, "model_fields", {})) if cls is not None else []


def format_validation_error(exc: ValidationError, model_cls=None) -> str:
    """One line: the first error, with its field path and, for unknown keys, a suggestion."""
    err = exc.errors()[0]
    loc = tuple(err.get("loc", ()))
    field = _loc_str(loc)
    if err["type"] == "extra_forbidden":
        key = str(loc[-1])
        names = _fields_at(model_cls, loc[:-1]) if model_cls is not None else []
        close = difflib.get_close_matches(key, names, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        return f"{field}: unknown key{hint}"
    if err["type"] == "missing":
        return f"{field}: required field is missing"
    msg = err["msg"]
    for prefix in ("Value error, ", "Assertion failed, "):
        msg = msg.removeprefix(prefix)
    bound = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}.get(err["type"])
    if bound is not None and err.get("ctx"):
        # "must be > 0 m, got -27 mm": the bound in the field's SI unit, the input as written
        limit = next(iter(err["ctx"].values()))
        unit = _field_unit(model_cls, loc) if model_cls is not None else ""
        msg = f"must be {bound} {limit:g}{' ' + unit if unit else ''}, got {err.get('input')}"
    n = len(exc.errors())
    more = f" (and {n - 1} more problem{'s' if n > 2 else ''})" if n > 1 else ""
    return f"{field}: {msg}{more}" if field else f"{msg}{more}"


def from_dict(data: dict, source: str = "model", base_dir=None):
    """Validate a dict (as read from TOML) into the model object of its ``kind``.

    ``base_dir`` (the model file's folder) reaches validators as ``info.context["base_dir"]``, so
    that file references inside a model resolve relative to the model file.
    """
    if not isinstance(data, dict):
        raise ModelError("a model must be a table of keys", field=source)
    kind = data.get("kind")
    if kind is None:
        raise ModelError(f"{source}: missing top-level 'kind' (one of {', '.join(KINDS)})")
    if kind == "study":
        raise ModelError(f"{source}: this is a study file: run it with 'drivedyn study {source}'")
    version = data.get("schema_version", SCHEMA_VERSION)
    if version != SCHEMA_VERSION:
        raise ModelError(f"{source}: schema_version {version!r} is not supported (this drivedyn reads {SCHEMA_VERSION})")
    pkg = analysis(kind)
    try:
        return pkg.Model.model_validate(data, context={"base_dir": Path(base_dir) if base_dir else Path.cwd()})
    except ValidationError as exc:
        raise ModelError(f"{source}: {format_validation_error(exc, pkg.Model)}") from None
    except ModelError as exc:
        raise ModelError(f"{source}: {exc}") from None


def loads(text: str, source: str = "model", base_dir=None):
    """Parse TOML text into a model object."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{source}: not valid TOML: {exc}") from None
    return from_dict(data, source, base_dir=base_dir)


def load(path):
    """Read and validate a model file (any kind).

    >>> import drivedyn
    >>> m = drivedyn.load(drivedyn.example_path("belt-5pk"))  # doctest: +SKIP
    """
    path = Path(path)
    if not path.exists():
        raise ModelError(f"{path}: file not found")
    if path.is_dir():
        raise ModelError(f"{path}: is a directory, expected a model file")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ModelError(f"{path}: cannot read: {exc}") from None
    return loads(text, source=str(path), base_dir=path.parent)


def to_dict(model) -> dict:
    """The model as plain data (SI floats), suitable for TOML."""
    return _drop_none(model.model_dump(mode="json"))


def _drop_none(obj):
    if isinstance(obj, dict):
        return {k: _drop_none(v) for k, v in obj.items() if v is not None}
    if isinstance(obj, list):
        return [_drop_none(v) for v in obj]
    return obj


def dumps(model) -> str:
    """TOML text of a model; loading it gives back an equal model."""
    import tomli_w

    return tomli_w.dumps(to_dict(model))


def save(model, path) -> Path:
    """Write a model to a TOML file."""
    path = Path(path)
    path.write_text(dumps(model), encoding="utf-8")
    return path


def replace(model, overrides: dict):
    """A copy of ``model`` with dotted-path overrides applied, revalidated.

    Paths use field names; list items are addressed by their ``name`` field when they have one
    (``pulleys.alternator.inertia``) or by index (``pulleys.1.inertia``).
    """
    data = to_dict(model)
    for path, value in overrides.items():
        set_path(data, path, value)
    return from_dict(data, source="override")


def set_path(data: dict, path: str, value) -> None:
    parts = path.split(".")
    node = data
    for i, part in enumerate(parts):
        last = i == len(parts) - 1
        if isinstance(node, list):
            idx = _list_index(node, part, path)
            if last:
                node[idx] = value
            else:
                node = node[idx]
            continue
        if not isinstance(node, dict):
            raise ModelError(f"cannot follow {part!r}", field=path)
        if last:
            node[part] = value
        else:
            if part not in node:
                node[part] = {}
            node = node[part]


def get_path(data: dict, path: str):
    node = data
    for part in path.split("."):
        if isinstance(node, list):
            node = node[_list_index(node, part, path)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise ModelError("no such field in the model", field=path)
    return node


def _list_index(node: list, part: str, path: str) -> int:
    for k, item in enumerate(node):
        if isinstance(item, dict) and item.get("name") == part:
            return k
    try:
        k = int(part)
    except ValueError:
        raise ModelError(f"no list item named {part!r}", field=path) from None
    if not -len(node) <= k < len(node):
        raise ModelError(f"index {k} out of range", field=path)
    return k
