"""A kernel compiled ahead in a second process: on a first run (numba's cache empty) the time loop's
kernel compiles there, into numba's on-disk cache, while this process settles the belt (whose own
kernels compile meanwhile); the run then loads it from the cache. numba compiles on one core: a
first run of the 5PK drive kept one of two cores busy for 36 s, and left the other idle.

``start(module, name, args, before)`` returns an ``Ahead`` (``wait()`` until the kernel is in the
cache), or None where there is nothing to compile ahead: the kernel is compiled or cached already,
numba's cache is off, or ``DRIVEDYN_COMPILE_AHEAD=0``. ``before`` ("module:function") is called in
the second process with ``(args, claims)`` ahead of the kernel: the kernel's callees compiled there,
shared with this process through ``Ahead.claims``, a directory both see (tail.py). Whatever goes
wrong in the second process, the run compiles the kernel itself, as without it."""
from __future__ import annotations

import importlib
import os
import pickle
import shutil
import subprocess
import sys
import tempfile


class Ahead:
    def __init__(self, proc, claims):
        self.proc = proc
        self.claims = claims

    def busy(self) -> bool:
        """Whether the second process still runs."""
        return self.proc.poll() is None

    def wait(self) -> bool:
        """Until the second process ends; True if it compiled the kernel into the cache."""
        ok = self.proc.wait() == 0
        shutil.rmtree(self.claims, ignore_errors=True)
        return ok

    def close(self):
        """End the second process if it still runs (a run refused or stopped before its loop)."""
        if self.proc.poll() is None:
            self.proc.terminate()
            self.proc.wait()
        shutil.rmtree(self.claims, ignore_errors=True)


def _types(dispatcher, args):
    return tuple(dispatcher.typeof_pyval(a) for a in args)


def cached(dispatcher, sig) -> bool:
    """Whether ``dispatcher`` has ``sig`` compiled, or in its on-disk cache (then it only loads).
    True where that cannot be told (no cache, numba's internals moved): nothing is done ahead."""
    if sig in dispatcher.overloads:
        return True
    try:
        cache = dispatcher._cache
        index = cache._cache_file._load_index()
        return cache._index_key(sig, dispatcher.targetctx.codegen()) in index
    except Exception:  # noqa: BLE001  (a NullCache: cache off; or an internal API that moved)
        return True


def start(module: str, name: str, args, before: str | None = None) -> Ahead | None:
    """Compile ``module.name`` for the types of ``args`` in a second process, unless cached."""
    if os.environ.get("DRIVEDYN_COMPILE_AHEAD", "1") == "0":
        return None
    dispatcher = getattr(importlib.import_module(module), name)
    if not hasattr(dispatcher, "typeof_pyval") or cached(dispatcher, _types(dispatcher, args)):
        return None        # (not a numba kernel: a test's stand-in)
    claims = tempfile.mkdtemp(prefix="drivedyn-compile-")
    try:
        # a fresh interpreter (not a fork: this process may hold threads and LLVM's state); it
        # needs the arguments' types only, but the arrays themselves pickle in a few kB
        proc = subprocess.Popen([sys.executable, "-m", __name__], stdin=subprocess.PIPE,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                env={**os.environ, "DRIVEDYN_COMPILE_AHEAD": "0"})
    except OSError:
        shutil.rmtree(claims, ignore_errors=True)
        return None
    try:
        with proc.stdin:
            proc.stdin.write(pickle.dumps((module, name, args, before, claims)))
    except OSError:      # it ended already: wait() says so, and the run compiles the kernel itself
        pass
    return Ahead(proc, claims)


def _main():
    module, name, args, before, claims = pickle.load(sys.stdin.buffer)
    if before:
        try:
            where, function = before.split(":")
            getattr(importlib.import_module(where), function)(args, claims)
        except Exception:  # noqa: BLE001  (the kernel compiles its callees itself)
            pass
    dispatcher = getattr(importlib.import_module(module), name)
    dispatcher.compile(_types(dispatcher, args))


if __name__ == "__main__":
    _main()
