"""The package version (one place: the package, its results and its report read it)."""
__version__ = "0.1.0"
