"""The package's import layering (pyproject.toml, [tool.importlinter]; docs/CONTRIBUTING.md draws it):
the belt package's layers, the analyses' independence and no import cycles anywhere. A change that
imports upward or closes a circle fails here, with import-linter's account of the offending chain."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_import_contracts_are_kept():
    out = subprocess.run([sys.executable, "-c", "import sys; from importlinter.cli import lint_imports_command as c; "
                          "sys.exit(c(['--config', 'pyproject.toml', '--no-cache']))"],
                         cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout[-4000:] + out.stderr[-2000:]
