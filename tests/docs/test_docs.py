"""The documentation site builds with warnings as errors (mkdocs build --strict): every page in
the navigation exists, every link between pages resolves, and the model-file reference is
generated from the model schema (so a field added to a model appears in it)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_docs_build_strict(tmp_path):
    pytest.importorskip("mkdocs")
    pytest.importorskip("material")
    if not (ROOT / "mkdocs.yml").exists():
        pytest.skip("not a source checkout (no mkdocs.yml)")
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(tmp_path / "site")],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-3000:]
    ref = (tmp_path / "site" / "reference" / "belt-drive.html").read_text()
    assert "pretension" in ref and "slip_margin_min" in ref and "model-reference:" not in ref
    assert "flap_speed_margin" in (tmp_path / "site" / "criteria.html").read_text()
    # the site browses from disk: navigation links name the page file, never a directory
    index = (tmp_path / "site" / "index.html").read_text()
    assert 'href="criteria.html"' in index and 'href="criteria/"' not in index


def test_readme_short_and_commands():
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 160
    assert 'pip install . && drivedyn run examples/belt-5pk.toml -o out' in text
    assert 'pip install ".[test]" && python -m pytest' in text
    assert "pip install \".[test]\" && python -m pytest" in (ROOT / ".ci" / "run").read_text()
    # the manual browsed from disk (site/index.html) or served while it is edited
    assert "site/index.html" in text and "mkdocs serve" in text
