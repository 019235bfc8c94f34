"""ISO 6336-2/-3 ratings: pitting and root safety factors of a mesh (mesh.py) and of a planetary
stage's meshes (planetary.py). Imports the mesh room only."""
