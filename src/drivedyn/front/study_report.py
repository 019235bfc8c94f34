"""``report.html`` of a study and of an optimisation: the cases that warned or did not finish, named
by their parameters in the study's own units; the criteria over the cases; every collected summary
key as its smallest and largest value over the finished cases, in engineering units, with the
case of the largest; the study's plots and the study file. The page is report.py's template.
"""
from __future__ import annotations

import math

from pathlib import Path

import numpy as np

from ..study.shown import case_names, shown_unit

#: at most this many components of a list-valued key get a row each (the rest: study.nc)
COMPONENTS = 6
#: at most this many cases that warned or did not finish are listed
LISTED = 50


def _num(v) -> str:
    if v is None or not np.isfinite(v):
        return "-"
    text = f"{v + 0.0:.4g}"
    return text[1:] if text.startswith("-") and not any(c in "123456789" for c in text) else text


def _words(part: str) -> str:
    """A key's part as words where it is one ('force_nominal' -> 'force nominal'); a symbol as it is
    ('K_Hbeta', 'S_H_m12')."""
    return part.replace("_", " ") if part == part.lower() else part


def _component_names(key: str, m: int) -> list[str]:
    last = key.rsplit(".", 1)[-1].lower()
    if m in (2, 3) and any(w in last for w in ("centre", "center", "position", "pivot")):
        return ["x", "y", "z"][:m]
    if "frequenc" in last or "mode" in last or "damping_ratio" in last:
        return [f"mode {i + 1}" for i in range(m)]
    return [f"[{i}]" for i in range(m)]


def _completed(ds):
    return np.isin(ds["status"].values, ("success", "warning"))


def _spread(ds, name, done, names):
    """Rows (label suffix, smallest, largest, largest-at) of a numeric variable over the finished cases."""
    var = ds[name]
    case_dims = ds["status"].dims
    extra = [d for d in var.dims if d not in case_dims]
    if len(extra) > 1 or any(d not in var.dims for d in case_dims):
        return []
    _, scale = shown_unit(ds, name)
    values = var.transpose(*case_dims, *extra).values.astype(float) * scale
    flat = values.reshape(done.size, -1)
    parts = _component_names(str(var.attrs.get("long_name", name)), flat.shape[1]) if extra else [""]
    rows = []
    for j, part in enumerate(parts[:COMPONENTS]):
        col = np.where(done.ravel(), flat[:, j], np.nan)
        if not np.isfinite(col).any():
            continue
        lo, hi = np.nanmin(col), np.nanmax(col)
        at = names[int(np.nanargmax(col))] if hi > lo else "every case"
        rows.append((part, lo, hi, at))
    if len(parts) > COMPONENTS:
        rows.append((f"... {len(parts) - COMPONENTS} more", None, None, "study.nc"))
    return rows


def criteria_table(ds, names) -> dict | None:
    """The criteria the cases were judged by: value over the finished cases, limit, and in how many
    of them it passed."""
    done = _completed(ds).ravel()
    crit = sorted({str(ds[v].attrs.get("long_name", v)).split(".")[1] for v in ds.data_vars
                   if str(ds[v].attrs.get("long_name", v)).startswith("criteria.")
                   and str(ds[v].attrs.get("long_name", v)).endswith(".value")})
    rows = []
    for c in crit:
        var = _var(ds, f"criteria.{c}.value")
        if var is None or ds[var].dtype.kind not in "fiub":
            continue
        spread = _spread(ds, var, _completed(ds), names)
        if not spread:
            continue
        _, lo, hi, _ = spread[0]
        unit, scale = shown_unit(ds, var)
        kind = _var(ds, f"criteria.{c}.kind")
        worst_min = next((str(k) for k in ds[kind].values.ravel() if k), "min") == "min" if kind else True
        col = np.where(done, ds[var].values.ravel().astype(float), np.nan)
        at = names[int(np.nanargmin(col) if worst_min else np.nanargmax(col))] if hi > lo else "every case"
        limit = _var(ds, f"criteria.{c}.limit")
        lim = ds[limit].values.ravel()[done].astype(float) * scale if limit and ds[limit].dtype.kind in "fiub" else []
        lim = lim[np.isfinite(lim)] if len(lim) else lim
        lim_text = "-" if not len(lim) else (_num(lim.min()) if lim.min() == lim.max() else f"{_num(lim.min())} .. {_num(lim.max())}")
        ok = _var(ds, f"criteria.{c}.pass")
        passes = "-"
        if ok and ds[ok].dtype.kind in "fiub":
            p = ds[ok].values.ravel()[done].astype(float)
            passes = f"{int(np.nansum(p == 1))} of {int(np.isfinite(p).sum())}"
        text = _var(ds, f"criteria.{c}.text")
        what = next((str(t) for t in ds[text].values.ravel() if t), "") if text else ""
        rows.append([c, _num(lo), _num(hi), lim_text, unit, passes, at, what])
    if not rows:
        return None
    return {"title": "criteria over the finished cases", "rows": rows,
            "head": ["criterion", "smallest", "largest", "limit", "unit", "cases passing", "worst at", "what it judges"],
            "note": "each case's verdict: criteria.*.pass in study.nc"}


def _var(ds, key):
    """The Dataset variable of summary key ``key`` (collect names it by the key, made netCDF-safe)."""
    for v in ds.data_vars:
        if ds[v].attrs.get("long_name") == key:
            return v
    return None


def result_tables(ds, names) -> list[dict]:
    """One table per top-level part of the summary (meshes, pulleys, spans, rating, ...): each
    numeric key's smallest and largest value over the finished cases, its unit and the case of the
    largest; the criteria have their own table."""
    done = _completed(ds)
    keys = [k for k in ds.attrs.get("summary_keys", "").split("\n") if k and k in ds.data_vars]
    groups: dict[str, list] = {}
    for name in keys:
        var = ds[name]
        key = str(var.attrs.get("long_name", name))
        if key.startswith("criteria.") or var.dtype.kind not in "fiub":
            continue
        head, _, rest = key.partition(".")
        group, label = (head, rest) if rest else ("drive", head)
        unit, _ = shown_unit(ds, name)
        for part, lo, hi, at in _spread(ds, name, done, names):
            words = " · ".join(_words(x) for x in label.split(".")) + (f" {part}" if part else "")
            if lo is None:
                groups.setdefault(group, []).append([words, "", "", "", at])
            elif at == "every case":
                groups.setdefault(group, []).append([words, _num(lo), "(every case)", unit, ""])
            else:
                groups.setdefault(group, []).append([words, _num(lo), _num(hi), unit, at])
    return [{"title": f"{_words(g)}: over the finished cases", "rows": rows,
             "head": ["quantity", "smallest", "largest", "unit", "largest at"], "note": ""}
            for g, rows in groups.items()]


def parameter_rows(ds) -> list[dict]:
    """The study's parameters, their values in the study's units and the model fields they set."""
    from ..study.shown import parameter_names

    rows = []
    for p in parameter_names(ds):
        if p not in ds.coords:
            continue
        unit, scale = shown_unit(ds, p)
        vals = ds[p].values.ravel().tolist()
        nums = [v * scale for v in vals if isinstance(v, float)]
        if nums and len(nums) == len(vals):
            text = (", ".join(_num(v) for v in nums) if len(nums) <= 8
                    else f"{_num(min(nums))} .. {_num(max(nums))} ({len(nums)} values)")
        else:
            text = ", ".join(str(v) for v in vals[:8]) + (f" ... ({len(vals)} values)" if len(vals) > 8 else "")
        paths = ds[p].attrs.get("paths", "")
        rows.append({"key": p + (f" ({paths})" if paths and paths != p else ""), "value": text, "unit": unit})
    return rows


def write_study_report(res, study_file, outdir) -> Path:
    """``outdir/report.html`` for a study: case counts, the cases that warned or did not finish,
    the criteria and every collected key over the cases, the parameters, every study plot, and the
    study file."""
    from ..core.outputs import file_stem, write_text
    from ..study.collect import unmatched_lines
    from .report import _figures, render

    ds = res.ds
    c = res.counts
    sts = ds["status"].values.ravel()
    msgs = ds["message"].values.ravel()
    names = case_names(ds)
    bad = [(str(st), f"{name}: {m}") for st, m, name in zip(sts, msgs, names) if st != "success"]
    diags = [{"code": st, "text": text, "quantity": ""} for st, text in bad[:LISTED]]
    if len(bad) > LISTED:
        diags.append({"code": "more", "text": f"{len(bad) - LISTED} more cases that warned or did not finish: the "
                                              "status and message variables of study.nc", "quantity": ""})
    diags += [{"code": "outputs", "text": line, "quantity": ""} for line in unmatched_lines(ds)]
    total = c.get("total", len(sts))
    warned = c.get("warning", 0)
    message = (f"{total} cases: {c.get('success', 0)} succeeded, {warned} warned, "
               f"{total - c.get('success', 0) - warned} did not finish"
               + (f" ({c['ran']} run now, {c['cached']} from the cache)" if "ran" in c and "cached" in c else ""))
    status = "success" if c.get("success", 0) == total else ("warning" if not any(
        st not in ("success", "warning") for st in sts) else "failed")
    tables = [t for t in [criteria_table(ds, names)] if t] + result_tables(ds, names)
    captions = {}
    for p in res.plots or []:
        key = next((k for k in ds.data_vars if file_stem(k.replace(".", "_")) == Path(p).stem), Path(p).stem)
        unit = shown_unit(ds, key)[0] if key in ds else ""
        captions[Path(p).name] = (f"{key}{f' ({unit})' if unit else ''} of every case against the study's "
                                  "parameters; cases that warned or failed are marked and left blank (see "
                                  "Diagnostics for why).")
    html = render(title=f"study: {ds.attrs.get('title') or Path(study_file).stem}", kind="parameter study", status=status,
                  message=message, diagnostics=diags, headline=[], results=[], tables=tables,
                  figures=_figures(res.plots, captions), model_rows=parameter_rows(ds),
                  model_toml=ds.attrs.get("study_toml", ""), source=str(study_file), model_heading="Parameters")
    return write_text(Path(outdir) / "report.html", html)


def write_optimisation_report(res, study, study_file, outdir, hits=()) -> Path:
    """``outdir/report.html`` for an optimisation: the best design, its objective and constraint
    margins, the designs evaluated, an optimum on a bound of its range (said as a diagnostic), the
    convergence plot and the study file; values in the study's units."""
    from ..core.outputs import write_text
    from .report import _figures, render

    o = res.optimum
    opt = study.spec.optimise
    n = len(o.evaluations)
    feasible = sum(1 for e in o.evaluations if e.feasible)
    rows = [{"key": "designs evaluated", "value": str(n), "unit": ""},
            {"key": "feasible designs", "value": str(feasible), "unit": ""}]
    diags = [{"code": "optimum-on-bound", "quantity": h["name"], "value": f"{h['value']:.6g}", "limit": f"{h['bound']:.6g}",
              "unit": f" {h['unit']}" if h["unit"] not in ("", "1") else "",
              "text": f"the best design sits on the {h['side']} bound of this parameter's range (within "
                      f"{100 * h['share']:g} % of its range): the optimum may lie outside the range; widen it"} for h in hits]
    if o.values is None:
        status, message = "failed", "no feasible design: widen the ranges, loosen the constraints or raise the budget"
    else:
        status, message = ("warning" if hits else "success"), f"best {opt.objective} = {o.objective:.6g}"
        rows.append({"key": f"objective ({opt.sense}): {opt.objective}", "value": f"{o.objective:.6g}", "unit": ""})
        st = o.start
        if st and math.isfinite(st.get("objective", math.nan)):
            rows.append({"key": "the base file's design (no parameter changed)" + ("" if st["feasible"] else ", infeasible"),
                         "value": f"{st['objective']:.6g}" + (f" (the best: {100 * o.objective / st['objective']:.3g} %)"
                                                              if st["objective"] else ""), "unit": ""})
        for k, v in o.values.items():
            unit, scale = study_unit(study, k)
            rows.append({"key": k, "value": f"{v * scale:.6g}" if isinstance(v, float) else str(v), "unit": unit})
        for key, c in o.constraints.items():
            if "value" in c:
                bounds = " ".join(f"{side} {c[side]:.4g}" for side in ("min", "max") if side in c)
                rows.append({"key": f"constraint {key} ({bounds})", "value": f"{c['value']:.4g} (margin {c['margin']:.4g})",
                             "unit": ""})
    params = [{"key": p.label, "value": f"{p.range[0]} .. {p.range[1]}" if p.range is not None else str(p.values),
               "unit": f"{p.scale}{', integer' if p.integer else ''}"} for p in study.spec.parameters]
    text = res.ds.attrs.get("study_toml", "") if getattr(res, "ds", None) is not None else ""
    captions = {Path(p).name: "the best feasible objective against the designs evaluated; dots: each feasible design"
                for p in res.plots or []}
    tables = []
    sr = getattr(res, "speed_range", None)
    if sr is not None:
        tables.append({"title": f"through the speed range: {sr.quantity}" + (f" ({sr.unit})" if sr.unit else ""),
                       "head": ["crank speed (rpm)", "the base file's design", "the best design", "best / base"],
                       "rows": [[f"{r:.0f}", _num(a), _num(b), f"{b / a:.3g}" if a else "-"]
                                for r, a, b in zip(sr.rpm, sr.base, sr.best)],
                       "note": "each design run once more in full, its run-up read bin by bin"})
        captions["speed_range.png"] = (f"{sr.quantity} in each crank-speed bin: the base file's design against the "
                                       "best design")
    html = render(title=f"optimisation: {study.name or Path(study_file).stem}", kind="optimisation study",
                  status=status, message=message, diagnostics=diags, headline=rows, results=[], tables=tables,
                  figures=_figures(res.plots, captions), model_rows=params, model_toml=text, source=str(study_file),
                  model_heading="Design space")
    return write_text(Path(outdir) / "report.html", html)


def study_unit(study, label) -> tuple[str, float]:
    """(unit, shown value per SI value) of parameter ``label`` as the study writes it."""
    if label in study.shown:
        return study.shown[label]
    unit = study.units.get(label, "") or ""
    return ("" if unit == "1" else unit), 1.0

