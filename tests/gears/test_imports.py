"""No import circles inside drivedyn.gears: a module never imports (at top level or inside a
function) a module that imports it back, directly or through others."""
import ast
from pathlib import Path

import drivedyn.gears

PKG = Path(drivedyn.gears.__file__).parent


def _graph() -> dict:
    g = {}
    for f in PKG.glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    deps.add(node.module.split(".")[0])
                else:                               # from . import a, b
                    deps.update(a.name for a in node.names)
        g[f.stem] = {d for d in deps if (PKG / f"{d}.py").exists()} - {f.stem}
    return g


def _cycle(g):
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for d in sorted(g.get(n, ())):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d not in state:
                c = visit(d)
                if c:
                    return c
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(g):
        if n not in state:
            c = visit(n)
            if c:
                return c
    return None


def test_no_import_circle_in_gears():
    g = _graph()
    assert "simulate" in g and "kernel_inputs" in g
    assert _cycle(g) is None, " -> ".join(_cycle(g))


def test_the_checker_finds_a_circle():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_lower_modules_stay_below_the_run():
    g = _graph()
    top = {"simulate", "plots", "report", "sweep", "checks"}
    for low in ("geometry", "iso6336", "rating", "planetary", "planetary_lateral", "planetary_rating", "gearbox",
                "train", "kernel_inputs"):
        seen, todo = set(), [low]
        while todo:
            for d in g.get(todo.pop(), ()):
                if d not in seen:
                    seen.add(d)
                    todo.append(d)
        assert not seen & top, f"{low} reaches {sorted(seen & top)}"
