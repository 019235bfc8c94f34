"""``python -m drivedyn`` runs the command-line interface."""
from drivedyn.cli import main

main()
