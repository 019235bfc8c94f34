"""A belt span's transverse vibration (seed 002, Belyaev): its properties and critical speed
(quantities.py), natural frequencies with bending and speed (frequencies.py), Mathieu tongues
(mathieu.py), Floquet multipliers (floquet.py, _kernels.py) and the stability chart (chart.py). Used
by the span-stability analysis and by the belt drive (installation, flap, span stability of a run)."""
