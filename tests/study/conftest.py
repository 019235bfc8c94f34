"""A real two-worker LocalCluster (processes) shared by the study tests, and study-file helpers."""
from __future__ import annotations

import logging
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BELT = ROOT / "examples" / "belt-5pk.toml"


@pytest.fixture(scope="session")
def client():
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                           silence_logs=logging.CRITICAL)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture
def write_study(tmp_path):
    """write_study(text, name="study.toml") -> path; ``{belt}`` in the text is the 5PK example's path."""

    def write(text: str, name: str = "study.toml") -> Path:
        path = tmp_path / name
        path.write_text(textwrap.dedent(text).replace("{belt}", BELT.as_posix()))
        return path

    return write
