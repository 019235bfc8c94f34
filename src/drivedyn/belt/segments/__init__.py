"""The discrete model of seed 000: the belt as a chain of rigid segments with Kelvin-Voigt joints,
penalty contact and friction, integrated by the implicit, semi-implicit or RKF45 scheme
(simulate.py runs it; system.py builds its arrays). Never imports the rotational model."""
