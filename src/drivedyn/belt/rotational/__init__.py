"""The rotational model: pulleys, rotors and tensioner arms with the spans as axial springs and
creep on the wraps (simulate.py), its compiled step (_kernels.py) and periodic run-ups
(periodic.py). Never imports the segment model."""
