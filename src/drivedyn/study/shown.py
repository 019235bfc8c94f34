"""A study's numbers as people read them: the parameters in the units the study file writes them
in ("120 deg", "1000 rpm"), the collected summary keys in engineering units (deg, rpm, mm, MPa),
for its report, its plots and its terminal lines alike. study.nc keeps SI (each variable's
``units``); a parameter's coordinate carries ``shown_units`` and ``shown_scale`` (the shown
value per SI value) beside it.
"""
from __future__ import annotations

import math

#: SI unit of a summary key -> (the unit engineers read, its value per SI value)
ENGINEERING = {
    "rad": ("deg", 180 / math.pi),
    "rad/s": ("rpm", 30 / math.pi),
    "rad/s^2": ("rpm/s", 30 / math.pi),
    "m": ("mm", 1e3),
    "m^2": ("mm^2", 1e6),
    "m/rad": ("mm/deg", 1e3 * math.pi / 180),
    "N*m/rad": ("N*m/deg", math.pi / 180),
    "Pa": ("MPa", 1e-6),
}

def parameter_names(ds) -> list[str]:
    """The study's parameters, exactly (``parameter_names``: JSON; older files: comma-separated)."""
    import json

    if "parameter_names" in ds.attrs:
        return list(json.loads(ds.attrs["parameter_names"]))
    return [p.strip() for p in ds.attrs.get("parameters", "").split(",") if p.strip()]


def shown_unit(ds, name) -> tuple[str, float]:
    """(unit, scale): how variable ``name`` of a study Dataset reads (value x scale, in unit). A
    parameter in its study's units; a summary key in the study's units where a parameter has the
    same SI unit, else in ENGINEERING's."""
    var = ds[name]
    si = var.attrs.get("units", "")
    if "shown_units" in var.attrs:
        return var.attrs["shown_units"], float(var.attrs.get("shown_scale", 1.0))
    if name in ds.coords:               # a parameter written in plain numbers: SI, as written
        return ("" if si == "1" else si), 1.0
    for c in ds.coords.values():        # a speed output in rpm when the study writes its speeds in rpm
        if c.attrs.get("units") == si and si and "shown_units" in c.attrs:
            return c.attrs["shown_units"], float(c.attrs.get("shown_scale", 1.0))
    return ENGINEERING.get(si, ("" if si == "1" else si, 1.0))


def in_shown_units(ds, names):
    """A copy of ``ds`` with the numeric variables ``names`` scaled to their shown units (attrs
    ``units`` the shown unit): what the plots draw."""
    out = ds.copy()
    for n in names:
        var = ds[n]
        unit, scale = shown_unit(ds, n)
        attrs = {k: v for k, v in var.attrs.items() if k not in ("shown_units", "shown_scale")}
        attrs["units"] = unit or ("1" if var.attrs.get("units") == "1" else "")
        values = var.values * scale if scale != 1 and var.dtype.kind in "fi" else var.values
        if n in ds.coords:
            out = out.assign_coords({n: (var.dims, values, attrs)})
        else:
            out[n] = (var.dims, values, attrs)
    return out


def value_text(v, unit="") -> str:
    text = f"{v:.4g}" if isinstance(v, float) else str(v)
    return text + (f" {unit}" if unit not in ("", "1") else "")


def parameter_text(ds, name, v) -> str:
    """'drive.speed = 1000 rpm': a parameter's SI value ``v`` in the study's units."""
    unit, scale = shown_unit(ds, name)
    if isinstance(v, float):
        v = v * scale
    return f"{name} = {value_text(v, unit)}"


def case_names(ds) -> list[str]:
    """'clocking_angle = 128.6 deg, drive.speed = 1000 rpm' per case, in the order of
    ``status.ravel()``: a grid's cases by their coordinates, a sampled design's by the parameters
    along ``case`` (in the study's units)."""
    import itertools

    dims = list(ds["status"].dims)
    if dims == ["case"]:
        params = [p for p in parameter_names(ds) if p in ds.coords and ds[p].dims == ("case",)]
        if not params:
            return [f"case {k}" for k in range(ds["status"].size)]
        return [f"case {k}: " + ", ".join(parameter_text(ds, p, ds[p].values[k].item()) for p in params)
                for k in range(ds["status"].size)]
    if any(d not in ds.coords for d in dims):
        return [f"case {k}" for k in range(ds["status"].size)]
    return [", ".join(parameter_text(ds, d, v) for d, v in zip(dims, combo))
            for combo in itertools.product(*(ds[d].values.tolist() for d in dims))]
