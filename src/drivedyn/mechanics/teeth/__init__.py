"""Timing-belt teeth and pulley grooves (seed 001, Pakula): contours (contour.py), the HTD, GT, T, L
profiles (profiles.py) and their catalogue (catalogue.py), the pulley's grooves (pulley.py), the
tooth's path into its groove (kinematics.py), a belt/pulley pair and its checks (pair.py), the
interference of a pair (interference.py, _kernels.py), the quasi-static load sharing over a wrap and
the climb criterion (loadshare.py). Used by the toothed-mesh analysis and the belt drive's teeth."""
