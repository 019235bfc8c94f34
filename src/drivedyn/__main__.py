"""``python -m drivedyn`` runs the command-line interface."""
from drivedyn.front.cli import main

main()
