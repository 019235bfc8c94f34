"""What `drivedyn check` and `import drivedyn.front.cli` import, in a fresh interpreter: not the modules
a check does not use (scipy.optimize's import was a quarter of check's wall time)."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("scipy.optimize", "scipy.sparse", "xarray", "matplotlib", "numba")


def _imported_after(code: str) -> set[str]:
    probe = f"{code}\nimport json, sys\nprint(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))"
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return set(json.loads(out.splitlines()[-1]))


def test_import_of_the_cli_imports_no_numerics():
    assert _imported_after("import drivedyn.front.cli") == set()


@pytest.mark.parametrize("args", [["check"], ["check", "--json"]])
def test_check_imports_no_numerics_it_does_not_run(args):
    # nor numba: importing it and loading the compiled placement walk was a third of check's wall
    # time; check walks the belt's path interpreted (a tensioner's equilibrium at rest: 60 walks)
    code = f"from drivedyn.front.cli import main\ntry:\n    main({args + ['examples/fead-runup.toml']!r})\nexcept SystemExit:\n    pass"
    assert _imported_after(code) == set()
