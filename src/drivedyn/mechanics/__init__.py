"""Mechanics more than one analysis uses, below the analyses (each analysis imports downward only):

- ``layout``: the belt's path on the pulleys' pitch circles (spans as common tangents, wraps, length);
- ``pitch_curves``, ``curve_layout``, ``curve_turn``: non-circular convex pitch curves (an oval crank
  sprocket, a table of radius against angle), the belt's path on them at given pulley angles, and
  that path over a turn;
- ``teeth``: timing-belt tooth and groove profiles, their catalogue, the profile pair and its
  interference check, the quasi-static tooth load sharing and the climb (jump) criterion;
- ``span``: a belt span's transverse frequencies with bending and speed, its Mathieu / Floquet
  stability charts and critical speed.

Each analysis stays the owner of its model file, its runs and its outputs; nothing here imports an
analysis (functions that read a model take the few attributes they need)."""
