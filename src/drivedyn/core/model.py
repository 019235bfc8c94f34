"""Model files: TOML in, validated frozen objects out, and back.

Every analysis defines its model as a subclass of :class:`Spec` with a top-level
``kind: Literal[...]`` and ``schema_version``. Physical fields are declared with
:func:`quantity`, which accepts a number (taken in SI) or a string with a unit, converted
once here. Unknown keys are errors that suggest the nearest valid name.

    from drivedyn.core.model import Spec, quantity
    class Pulley(Spec):
        name: str
        radius: quantity("m", gt=0)
"""
from __future__ import annotations

import ast
import difflib
import functools
import inspect
import re
import tomllib
from pathlib import Path
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError

from .analyses import KINDS, analysis  # noqa: F401  (re-exported: the registry lives in analyses.py)
from .errors import ModelError
from .units import finite, to_si

SCHEMA_VERSION = 1
#: longest list a model file may hold: the longest legitimate one is a measured table (a few
#: thousand rows); 100 000 entries would only cost validation time (longer series go in a CSV)
MAX_LIST = 10_000
#: largest model file read (bytes): 10 000 table rows take about 0.2 MB, and parsing TOML costs
#: about 0.3 s per MB, so anything larger is refused before it is parsed
MAX_BYTES = 2_000_000
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
#: deepest nesting of tables and lists: the schemas nest 4 levels; 1000 would exhaust the stack
MAX_DEPTH = 32


class Spec(BaseModel):
    """Base of every model object: frozen, unknown keys forbidden, defaults validated, and no
    NaN or inf in any float field (quantities are refused earlier, in ``units.to_si``).

    Every field has a docstring on the line below it saying what it means (:func:`field_docs`
    reads them for the schema and the model-file reference)."""

    model_config = ConfigDict(extra="forbid", frozen=True, validate_default=True, allow_inf_nan=False)


@functools.lru_cache(maxsize=None)
def _module_field_docs(path: str) -> dict[str, dict[str, str]]:
    """{class name: {field: docstring}} of the top-level classes of one source file, parsed once."""
    tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    out = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            out[node.name] = {a.target.id: inspect.cleandoc(b.value.value) for a, b in zip(node.body, node.body[1:])
                              if isinstance(a, ast.AnnAssign) and isinstance(a.target, ast.Name)
                              and isinstance(b, ast.Expr) and isinstance(b.value, ast.Constant)
                              and isinstance(b.value.value, str)}
    return out


def field_docs(cls) -> dict[str, str]:
    """{field: its docstring} of a model class, inherited fields included: the string literal on the
    line below each field. Read from the source when asked (the schema, the reference), not at
    import: pydantic's ``use_attribute_docstrings`` would do the same for every class at import,
    0.35 s of drivedyn's start-up on Python 3.11."""
    docs = {}
    for c in reversed(cls.__mro__):
        if not (isinstance(c, type) and issubclass(c, BaseModel)) or c is BaseModel or "<" in c.__qualname__:
            continue
        try:
            path = inspect.getsourcefile(c)
        except TypeError:
            continue
        if path:
            docs.update(_module_field_docs(path).get(c.__qualname__, {}))
    return docs


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


#: pydantic's bounds as JSON Schema's keywords, and as they read in a message
_BOUNDS = {"gt": ("exclusiveMinimum", ">", lambda x, b: x > b), "ge": ("minimum", ">=", lambda x, b: x >= b),
           "lt": ("exclusiveMaximum", "<", lambda x, b: x < b), "le": ("maximum", "<=", lambda x, b: x <= b)}


def limit(unit: str, why: str, **bounds):
    """A design limit or a standard's factor: a :func:`quantity` whose bounds keep the judgement
    conservative, refused with ``why`` beside them (docs/limits.md: a number that makes a standard's
    formula non-conservative, or a limit that can never fail, is refused, never silently used)."""
    shown = "" if unit in ("", "1") else f" {unit}"

    def check(value: float) -> float:
        for key, bound in bounds.items():
            if not _BOUNDS[key][2](value, bound):
                raise ValueError(f"must be {_BOUNDS[key][1]} {bound:.4g}{shown} ({why}), got {value:.4g}{shown}")
        return value

    from pydantic import AfterValidator

    extra = {"unit": unit, **{_BOUNDS[k][0]: b for k, b in bounds.items()}}
    return Annotated[float, BeforeValidator(_si_validator(unit)), AfterValidator(check), Field(json_schema_extra=extra)]


def table_rows(value, units: tuple[str, str], field: str, min_rows: int = 1) -> list[list[float]]:
    """Validate a table of rows [x, y] (numbers or unit strings) into SI floats, x increasing.

    For pydantic validators: raises ValueError with a one-line message.
    """
    if not isinstance(value, (list, tuple)) or len(value) < min_rows:
        raise ValueError(f"{field} must be a list of at least {min_rows} [{units[0]}, {units[1]}] row(s)")
    if len(value) > MAX_LIST:
        raise ValueError(f"{field} has {len(value)} rows, more than {MAX_LIST}")
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


def _loc_str(loc) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


# Walking the schema: one step at a time from a model class through fields, list items and tuple
# entries, carrying the unit a quantity() declares down to the items of its list or tuple. Used
# for error messages (the unit of a bound, suggestions for unknown keys) and by studies (the unit
# of a parameter path).

def unwrap(ann):
    """Strip Optional and Annotated layers; returns (core annotation, unit found or None)."""
    import types
    import typing

    unit = None
    while True:
        origin = typing.get_origin(ann)
        if origin is typing.Annotated:
            for meta in ann.__metadata__:
                extra = getattr(meta, "json_schema_extra", None)
                if isinstance(extra, dict) and extra.get("unit"):
                    unit = extra["unit"]
            ann = typing.get_args(ann)[0]
        elif origin is typing.Union or origin is types.UnionType:
            args = [a for a in typing.get_args(ann) if a is not type(None)]
            if len(args) != 1:
                return ann, unit
            ann = args[0]
        else:
            return ann, unit


class _Unit:
    """Annotated marker carrying a field's unit down into list/tuple items."""

    def __init__(self, unit):
        self.json_schema_extra = {"unit": unit}


def schema_step(ann, part):
    """Annotation one path step (a field name or an item index) below ``ann``, or None."""
    import typing

    part = str(part)
    core, unit = unwrap(ann)
    if isinstance(core, type) and issubclass(core, BaseModel):
        f = core.model_fields.get(part)
        if f is None:
            return None
        extra = f.json_schema_extra if isinstance(f.json_schema_extra, dict) else {}
        sub = f.annotation
        for m in f.metadata:  # quantity() as a whole field annotation is merged into the FieldInfo
            e = getattr(m, "json_schema_extra", None)
            if isinstance(e, dict) and e.get("unit"):
                extra = e
        return typing.Annotated[sub, _Unit(extra["unit"])] if extra.get("unit") else sub
    if typing.get_origin(core) in (list, tuple):
        args = [a for a in typing.get_args(core) if a is not Ellipsis]
        if not args:
            return None
        item = args[int(part)] if typing.get_origin(core) is tuple and part.isdigit() and int(part) < len(args) else args[0]
        return typing.Annotated[item, _Unit(unit)] if unit else item
    return None


def schema_at(model_cls, path):
    """Annotation reached from ``model_cls`` along ``path`` (dotted string or parts), or None."""
    ann = model_cls
    for part in (path.split(".") if isinstance(path, str) else path):
        ann = schema_step(ann, part)
        if ann is None:
            return None
    return ann


def field_unit(model_cls, path) -> str | None:
    """SI unit of the field at ``path`` (declared with ``quantity``), or None."""
    ann = schema_at(model_cls, path)
    return None if ann is None else unwrap(ann)[1]


def _fields_at(model_cls, loc):
    """Field names of the model class reached by following ``loc`` (for suggestions)."""
    ann = schema_at(model_cls, loc)
    core = unwrap(ann)[0] if ann is not None else None
    return list(core.model_fields) if isinstance(core, type) and issubclass(core, BaseModel) else []


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
    if err["type"] == "finite_number":
        return f"{field}: must be a finite number, got {err.get('input')}"
    msg = err["msg"]
    for prefix in ("Value error, ", "Assertion failed, "):
        msg = msg.removeprefix(prefix)
    bound = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}.get(err["type"])
    if bound is not None and err.get("ctx"):
        # "must be > 0 m, got -27 mm": the bound in the field's SI unit, the input as written
        limit = next(iter(err["ctx"].values()))
        unit = (field_unit(model_cls, loc) or "") if model_cls is not None else ""
        unit = "" if unit == "1" else unit        # a ratio: "must be >= 0", not ">= 0 1"
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
    _screen(data, source)
    kind = data.get("kind")
    if kind is None:
        raise ModelError(f"{source}: missing top-level 'kind' (one of {', '.join(KINDS)})")
    if not isinstance(kind, str):
        raise ModelError(f"{source}: kind: must be a string (one of {', '.join(KINDS)}), got {kind!r:.40}")
    if kind == "study":
        raise ModelError(f"{source}: this is a study file: run it with 'drivedyn study {source}'")
    version = data.get("schema_version", SCHEMA_VERSION)
    if version != SCHEMA_VERSION:
        raise ModelError(f"{source}: schema_version {version!r} is not supported (this drivedyn reads {SCHEMA_VERSION})")
    try:
        pkg = analysis(kind)
    except ModelError as exc:
        raise ModelError(f"{source}: {exc}") from None
    try:
        return pkg.Model.model_validate(data, context={"base_dir": Path(base_dir) if base_dir else Path.cwd()})
    except ValidationError as exc:
        raise ModelError(f"{source}: {format_validation_error(exc, pkg.Model)}") from None
    except ModelError as exc:
        raise ModelError(f"{source}: {exc}") from None


def _screen(data: dict, source: str) -> None:
    """One pass over the raw data before validation: every number finite and of sensible magnitude
    (``units.finite``; strings with units are checked the same way by ``units.to_si``), no list
    longer than MAX_LIST, nesting at most MAX_DEPTH (iterative: a deep file must not exhaust the
    stack). The message names the field: "belt.pretension: must be a finite number, got nan"."""
    stack = [(data, ())]
    while stack:
        node, loc = stack.pop()
        if len(loc) > MAX_DEPTH:
            raise ModelError(f"{source}: {_loc_str(loc[:3])}...: nested more than {MAX_DEPTH} levels deep")
        if isinstance(node, dict):
            stack.extend((v, loc + (str(k),)) for k, v in node.items())
        elif isinstance(node, list):
            if len(node) > MAX_LIST:
                raise ModelError(f"{source}: {_loc_str(loc)}: a list of {len(node)} entries, more than {MAX_LIST}")
            stack.extend((v, loc + (i,)) for i, v in enumerate(node))
        elif isinstance(node, str) and _CONTROL.search(node):
            # names and labels end up in netCDF, JSON and file names: no NUL, escape or other
            # control characters (tabs and newlines are harmless)
            raise ModelError(f"{source}: {_loc_str(loc)}: control character {_CONTROL.search(node).group()!r} in a string")
        elif isinstance(node, (int, float)) and not isinstance(node, bool):
            try:
                finite(node)
            except (ModelError, OverflowError) as exc:
                raise ModelError(f"{source}: {_loc_str(loc)}: {exc}") from None


def parse_toml(text: str, source: str = "model") -> dict:
    """TOML text to data; every failure is one ModelError line naming ``source``."""
    if len(text) > MAX_BYTES:
        raise ModelError(f"{source}: {len(text) / 1e6:.1f} MB is too large for a model file (at most {MAX_BYTES / 1e6:g} MB)")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{source}: not valid TOML: {_one_line(exc)}") from None
    except RecursionError:  # tomllib recurses per nested inline table or array
        raise ModelError(f"{source}: not valid TOML: nested too deeply") from None


def read_toml(path, what: str = "model") -> tuple[dict, str]:
    """(data, text) of a TOML file (a model or a study: ``what`` names it in messages)."""
    path = Path(path)
    text = read_capped(path, what)
    return parse_toml(text, str(path)), text


def read_capped(path, what: str = "model", limit: int = MAX_BYTES) -> str:
    """The UTF-8 text of a regular file of at most ``limit`` bytes, counted while reading (a
    device reports size 0 and never ends; a named pipe would block the open): every failure one
    ModelError line naming the file."""
    import os
    import stat

    path = Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise ModelError(f"{path}: file not found") from None
    except OSError as exc:
        raise ModelError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if stat.S_ISDIR(st.st_mode):
        raise ModelError(f"{path}: is a directory, expected a {what} file")
    if not stat.S_ISREG(st.st_mode):
        raise ModelError(f"{path}: not a regular file (a device, pipe or socket), expected a {what} file")
    too_large = f"{path}: too large for a {what} file (at most {limit / 1e6:g} MB)"
    if st.st_size > limit:
        raise ModelError(f"{path}: {st.st_size / 1e6:.1f} MB is too large for a {what} file (at most {limit / 1e6:g} MB)")
    try:
        # O_NONBLOCK: if the file was swapped for a pipe since the stat, the open does not wait
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as f:
            if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
                raise ModelError(f"{path}: not a regular file, expected a {what} file")
            data = f.read(limit + 1)
    except OSError as exc:
        raise ModelError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if len(data) > limit:
        raise ModelError(too_large)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ModelError(f"{path}: cannot read: not UTF-8 text ({exc.reason} at byte {exc.start})") from None


def loads(text: str, source: str = "model", base_dir=None):
    """Parse TOML text into a model object."""
    return from_dict(parse_toml(text, source), source, base_dir=base_dir)


def _one_line(exc) -> str:
    return " ".join(str(exc).split())


def load(path):
    """Read and validate a model file (any kind).

    >>> import drivedyn
    >>> m = drivedyn.load(drivedyn.example_path("belt-5pk"))  # doctest: +SKIP
    """
    data, _ = read_toml(path)
    return from_dict(data, str(path), base_dir=Path(path).parent)


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
        if path.strip() == "kind" and value != data.get("kind"):
            # a belt drive's fields read as a gear train's would list every field as a problem
            raise ModelError(f"the kind of a model cannot change (this is a {data.get('kind')} model, {value!r} "
                             "asked): write a model file of that kind (drivedyn examples lists one of each)",
                             field="kind")
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
