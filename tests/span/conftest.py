import copy

import pytest

from drivedyn.core.model import from_dict, set_path

# seed 002 (Belyaev): T10 span, density read as 3e3 kg/m^3 (printed 3e-3: misprint)
BASE = {
    "kind": "span-stability",
    "span": {"length": 0.3, "mass_per_length": 0.084, "bending_stiffness": 0.045},
    "operation": {"pretension": 100.0, "speed": 5.0},
    "excitation": {"teeth": 16, "pulley_radius": 0.024},
    "tooth_force": {"polynomial": [0.00139, 0.0337, -0.685, 2.89, -1.71, 7.29]},
    "chart": {"points": [30, 30], "zoom": {"points": [20, 20]}},
}


def make(**changes):
    """The seed's span with dotted-path changes (``a__b`` for ``a.b``; value None deletes)."""
    data = copy.deepcopy(BASE)
    for path, value in changes.items():
        path = path.replace("__", ".")
        if value is None:
            node = data
            *head, last = path.split(".")
            for p in head:
                node = node[p]
            node.pop(last, None)
        else:
            set_path(data, path, value)
    return from_dict(data)


@pytest.fixture(scope="session")
def span_model():
    return make


@pytest.fixture(scope="session")
def seed_span():
    from drivedyn.mechanics.span.quantities import SpanProperties

    return SpanProperties(0.3, 0.084, 0.045)
