"""The whole suite: hypothesis draws the same examples on every run (derandomize), so that a run that
passed passes again on a clean clone; HYPOTHESIS_PROFILE=explore draws new ones (a falsifying
example then prints the values to pin it with)."""
import os

from hypothesis import settings

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))


# The quick loop (`python -m pytest -m quick`, about a minute on two cores): every analysis's smallest
# example end to end, the command line's contract, the model files' round trips and the import
# layering. The same tests stay in the full suite; this only names a subset of them.
QUICK = (
    "tests/api/test_every_kind.py",
    "tests/api/test_cli_contract.py",
    "tests/test_layers.py",
    "tests/test_cli_imports.py",
    "tests/belt/test_errors.py::test_roundtrip_of_examples",
    "tests/gears/test_errors.py::test_roundtrip_of_example",
    "tests/span/test_seed_and_model.py::test_model_round_trip",
    "tests/toothed/test_model.py::test_examples_round_trip",
    "tests/docs/test_schema.py",
)


def pytest_collection_modifyitems(config, items):
    import pytest

    root = str(config.rootpath)
    for item in items:
        nodeid = item.nodeid if not item.nodeid.startswith(root) else item.nodeid[len(root) + 1:]
        if nodeid.startswith(QUICK):
            item.add_marker(pytest.mark.quick)
