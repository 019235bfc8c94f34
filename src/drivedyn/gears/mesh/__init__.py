"""One gear mesh: involute geometry (geometry.py), ISO 6336-1 stiffness and dynamic factor
(iso6336.py), the mesh stiffness over a mesh cycle (stiffness.py, potential_energy.py). Lowest room
of the gear package: it imports no other room."""
