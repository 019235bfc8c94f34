"""The segment model's kernels as its integrators call them: compiled for the records' types once per
run (``compiled``), and numba's first compile of them said on the progress line (``compile_note``)."""
from __future__ import annotations

from contextlib import contextmanager


#: seconds numba takes to compile each scheme's kernels on their first use (empty cache, the 5PK
#: drive), measured on two 2-core machines 2.5 times apart in speed (an Intel Xeon, an AMD EPYC):
#: the progress line says so meanwhile
COMPILE_SECONDS = {"implicit": "15-40", "semi-implicit": "10-25", "rkf45": "7-30"}


def _note(method):
    return f"compiling the {method} kernels (first use: {COMPILE_SECONDS[method]} s)"


@contextmanager
def compile_note(progress, method, now=False):
    """Within it, numba's first compile (a kernel not in its cache) is said on the progress line,
    so that a first run does not sit at 0 % without a word; ``now``: said at once (a second
    process compiles them, ahead.py)."""
    if progress is None:
        yield
        return
    if now:
        progress(0.0, _note(method))
        yield
        return
    from numba.core import event

    class Note(event.Listener):
        said = False

        def on_start(self, ev):
            if not self.said:
                self.said = True
                progress(0.0, _note(method))

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", Note()):
        yield


@contextmanager
def compile_said(text):
    """Within it, numba's first compile (a kernel not in its cache) is said once on stderr with
    ``text`` (``check``'s dynamic duty rows: check has no progress bar)."""
    import sys

    from numba.core import event

    class Note(event.Listener):
        said = False

        def on_start(self, ev):
            if not self.said:
                self.said = True
                print(f"drivedyn: {text}", file=sys.stderr, flush=True)

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", Note()):
        yield


def compiled(dispatcher, args):
    """The compiled entry of ``dispatcher`` for these argument types: calling it skips numba's
    type dispatch, which for the kernel's records costs about 28 us a call against 15 (one call per
    output sample). The dispatcher itself when numba's internals differ."""
    try:
        dispatcher.compile(tuple(dispatcher.typeof_pyval(a) for a in args))
        sig = tuple(dispatcher.typeof_pyval(a) for a in args)
        return dispatcher.overloads[sig].entry_point
    except Exception:   # an internal API that moved: the ordinary call still works
        return dispatcher
