"""How long drivedyn takes to read, or to refuse, the inputs its input fuzz (tests/api/test_fuzz.py)
holds to a contract: a 10 000-row table with units (20 000 cells), a 3 MB file refused before it
is parsed, a 100 000-row table refused, a power tower refused, a 2001-row duty cycle refused before
its rows are read. The tests hold the results right and the refusals within seconds; the speeds
are measured here, where a loaded machine does not fail a suite (a 0.07-0.14 s read once took
1.06 s of wall time in a full suite on two busy cores).

Run: python benchmarks/bench_inputs.py [repeats]   (CPU seconds of this process, the best of the
repeats, and the wall seconds; compare numbers measured back to back on one machine)
"""
import sys
import tempfile
import time
import tomllib
from pathlib import Path


def timed(fn, repeats):
    cpu, wall = [], []
    for _ in range(repeats):
        t0, w0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - t0)
        wall.append(time.perf_counter() - w0)
    return min(cpu), min(wall)


def main(repeats=5):
    import tomli_w

    import drivedyn
    from drivedyn.core.model import table_rows
    from drivedyn.core.units import registry, to_si

    registry()          # built once (most of a second in a fresh environment): start-up, not reading
    rows = [[f"{k / 7:.6g} rpm", f"{k % 13} kN*m"] for k in range(10_000)]
    tmp = Path(tempfile.mkdtemp())
    huge = tmp / "huge.toml"
    huge.write_text("kind = 'belt-drive'\n# " + "x" * 3_000_000 + "\n")
    data = tomllib.loads(drivedyn.example_path("belt-5pk").read_text())
    data["pulleys"][1]["torque_speed"] = [[f"{k} rad/s", "1 N*m"] for k in range(100_000)]
    long_table = tmp / "long.toml"
    long_table.write_text(tomli_w.dumps(data))
    duty = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    duty_rows = [{"crank_speed": "1000 rpm", "share": 1 / 2001, "power": {"A_C": "1 kW"}}] * 2001

    def refused(fn):
        def run():
            try:
                fn()
            except drivedyn.ModelError:
                return
            raise AssertionError("not refused")
        return run

    cases = {
        "10 000-row table with units, read": lambda: table_rows(rows, ("rad/s", "N*m"), "t"),
        "3 MB file, refused": refused(lambda: drivedyn.load(huge)),
        "100 000-row table, refused": refused(lambda: drivedyn.load(long_table)),
        "power tower '9**9**9 m', refused": refused(lambda: to_si("9**9**9 m", "m")),
        "2001-row duty cycle, refused": refused(lambda: drivedyn.replace(duty, {"duty_cycle.rows": duty_rows})),
    }
    for name, fn in cases.items():
        cpu, wall = timed(fn, repeats)
        print(f"{name:40s} cpu {cpu:8.4f} s   wall {wall:8.4f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
