"""What both dynamic models share: the compiled pulleys, clutches and tensioners (_bodies.py) and
their records (bodies.py), the Dataset variables and summary a run writes (outputs.py), the
diagnostics both run (checks.py, loadcheck.py), run-up bins and tables (runup.py)."""
