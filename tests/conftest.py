"""The whole suite: hypothesis draws the same examples on every run (derandomize), so that a run that
passed passes again on a clean clone; HYPOTHESIS_PROFILE=explore draws new ones (a falsifying
example then prints the values to pin it with)."""
import os

from hypothesis import settings

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))
