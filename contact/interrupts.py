"""Interruptions (Ctrl-C, SIGTERM) as one orderly path, the same for every job.

:func:`handled` turns SIGINT and SIGTERM into :class:`Interrupted` (a ``KeyboardInterrupt``, so every
``except BaseException``/``finally`` on the way out runs as it does for Ctrl-C); on the first signal the
local worker processes (every ``multiprocessing`` child: the local process pools) are stopped at once,
so no ``shutdown(wait=True)`` on the way out waits for a point to finish, and further signals are
ignored while the job cleans up. :func:`finish` then removes what is left (this process's
temporaries, children still running) and gives the one line to print.

Code on the way out may say what an interruption keeps (:func:`keep`: "finished points kept in DIR;
run again to resume"); the innermost statement wins. Pool workers call :func:`worker_signals` (a child
forked within :func:`handled` does so at once): a Ctrl-C reaches every process of the terminal's
group, and the workers leave it to their parent instead of printing their own tracebacks.
:func:`handlers_kept` puts the handlers back after a C library replaced them (gmsh).
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading

#: the signals a job handles, and the exit status for each (128 + signal number, as a shell reports it)
SIGNALS = (signal.SIGINT, signal.SIGTERM)
_KEPT = "ringcontact_kept"
_ACTIVE = [False]                        # is handled() in force in this process?


class Interrupted(KeyboardInterrupt):
    """A job stopped by a signal (``signum``); a ``KeyboardInterrupt``, so Ctrl-C handling applies."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)


def keep(exc: BaseException, text: str, where=None) -> None:
    """Note on an interruption ``exc`` what it keeps (the first note, from the innermost code, wins);
    ``where``: the folder the note is about; the note is told only if that folder is still there when the
    job ends (a temporary directory on the way out is not)."""
    if not getattr(exc, _KEPT, None):
        try:
            setattr(exc, _KEPT, (str(text), None if where is None else os.fspath(where)))
        except AttributeError:
            pass


def kept(exc: BaseException) -> str:
    """What ``exc`` was noted to keep (:func:`keep`), or ``""`` (none, or its folder is gone)."""
    text, where = getattr(exc, _KEPT, None) or ("", None)
    return text if where is None or os.path.isdir(where) else ""


def stop_children(grace_s: float = 0.0) -> int:
    """Stop every ``multiprocessing`` child of this process (SIGKILL after ``grace_s`` seconds of SIGTERM;
    0: at once); returns how many there were. Workers hold no result of their own: the parent stores them.
    """
    import multiprocessing

    children = multiprocessing.active_children()
    for p in children:
        (p.terminate if grace_s > 0 else p.kill)()
    for p in children:
        p.join(grace_s if grace_s > 0 else 2.0)
        if p.is_alive():
            p.kill()
            p.join(2.0)
    return len(children)


_PENDING = [0]                           # the signal being honoured (0: none)


def pending() -> int:
    """The signal being honoured (0: none). A job that failed in another way after the signal arrived (the
    interruption raised inside an import leaves a half-initialised module behind, whose next use fails) was
    interrupted: the dispatcher reports it so (``reports/cli/__init__.py``)."""
    return int(_PENDING[0])


def _raise(signum, frame):
    for s in SIGNALS:                    # once on the way out, further signals would only break the cleanup
        signal.signal(s, signal.SIG_IGN)
    _PENDING[0] = int(signum)
    stop_children()
    raise Interrupted(signum)


def _again(signum, frame):
    """The signal's exception was swallowed (see :func:`_unraisable`): raise it again, now in ordinary code."""
    if _PENDING[0]:
        raise Interrupted(_PENDING[0])


def _unraisable(hook):
    """A ``sys.unraisablehook`` that catches :class:`Interrupted` raised where Python ignores exceptions (a
    function run at fork, ``logging``'s lock release, or a C library's callback into Python, such as
    llvmlite's object cache while numba compiles): Python would print "Exception ignored" with a traceback
    and go on computing. Instead the main thread is signalled again 10 ms later (SIGALRM, :func:`_again`), which
    raises the interruption in ordinary code (swallowed again: the same once more)."""
    def unraisable(args):
        if isinstance(args.exc_value, Interrupted):
            if threading.current_thread() is threading.main_thread():
                signal.setitimer(signal.ITIMER_REAL, 0.01)   # shortly, once out of the context that swallowed it
            else:
                import _thread
                _thread.interrupt_main(signal.SIGALRM)
            return
        hook(args)
    return unraisable


@contextlib.contextmanager
def handled():
    """Within the block, SIGINT and SIGTERM raise :class:`Interrupted` (see the module docstring); the
    previous handlers come back afterwards. Outside the main thread (where signals cannot be handled) a
    no-op."""
    if threading.current_thread() is not threading.main_thread() or _ACTIVE[0]:
        yield
        return
    previous = {s: signal.signal(s, _raise) for s in SIGNALS}
    previous[signal.SIGALRM] = signal.signal(signal.SIGALRM, _again)
    hook, sys.unraisablehook = sys.unraisablehook, _unraisable(sys.unraisablehook)
    _ACTIVE[0] = True
    try:
        yield
    finally:
        _ACTIVE[0] = False
        _PENDING[0] = 0
        signal.setitimer(signal.ITIMER_REAL, 0)
        sys.unraisablehook = hook
        for s, h in previous.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)


def _forked() -> None:
    """In a child forked while :func:`handled` is in force (a pool worker): not the parent's handlers."""
    if _ACTIVE[0]:
        _ACTIVE[0] = False
        worker_signals()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forked)


@contextlib.contextmanager
def handlers_kept():
    """Run a call of a C library that installs signal handlers of its own inside this block; the handlers in
    place before it are installed again after it. ``gmsh.initialize()`` sets SIGTERM to its default action
    (the process dies without a word, leaving its temporaries), and SIGINT too unless ``interruptible=False``.
    Outside the main thread a no-op."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    before = {s: signal.getsignal(s) for s in SIGNALS}
    try:
        yield
    finally:
        for s, h in before.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)


#: whether :func:`finish` reported an interruption in this process (:func:`pending_at_exit`)
_REPORTED = [False]


def finish(exc: KeyboardInterrupt) -> tuple[int, str]:
    """After an interruption: remove this process's temporaries and stop its children; return the exit
    status (130 for SIGINT, 143 for SIGTERM) and the line's text, ``interrupted (SIGINT): WHAT WAS KEPT``."""
    from contact.files import discard_own_temporaries

    signum = getattr(exc, "signum", signal.SIGINT)
    _PENDING[0] = 0                      # honoured: a swallowed copy is not raised again
    if threading.current_thread() is threading.main_thread():
        signal.setitimer(signal.ITIMER_REAL, 0)
    discard_own_temporaries()
    stop_children()
    what = kept(exc) or "no output half-written (every file is written whole or not at all); run again"
    _REPORTED[0] = True
    return 128 + int(signum), f"interrupted ({signal.Signals(signum).name}): {what}"


def in_thread(func, *args, **kwargs):
    """``func(*args, **kwargs)`` run in a thread of its own while this (main) thread waits for it in Python, so a
    signal is honoured at once even during a long compiled call that releases the GIL (numba ``nogil``, such as
    the production step loop): a signal is handled only between Python instructions of the main thread, which
    a compiled loop of 20 s in the main thread would hold back for those 20 s. On an interruption the thread
    is left computing a result nobody will keep (the dispatcher ends the process without waiting for it,
    :func:`busy_threads`). Outside :func:`handled`, or from another thread, a plain call."""
    if not _ACTIVE[0] or threading.current_thread() is not threading.main_thread():
        return func(*args, **kwargs)
    box = {}

    def target():
        try:
            box["value"] = func(*args, **kwargs)
        except BaseException as exc:     # noqa: BLE001 - handed to the caller as it is
            box["error"] = exc

    worker = threading.Thread(target=target, name=f"ringcontact-{getattr(func, '__name__', 'work')}")
    worker.start()
    while worker.is_alive():
        worker.join(0.05)
    if "error" in box:
        raise box["error"]
    return box["value"]


def pending_at_exit() -> bool:
    """An interruption was reported in this process (:func:`finish` ran): its job has said its one line."""
    return _REPORTED[0]


def quiet_shutdown() -> None:
    """After the one line of an interruption, the interpreter's shutdown prints nothing more: an object whose
    finaliser fails (measured: ``ringcontact orbit`` interrupted by Ctrl-C while numba compiled in a fresh cache, at
    load 5 on 2 cores: "Exception ignored in" and a traceback from llvmlite's ``ObjectRef.close`` after the job's
    line, tests/reports/test_interrupts.py) is dropped silently, as the rest of the unfinished work is."""
    sys.unraisablehook = _silent


def _silent(args) -> None:
    """A ``sys.unraisablehook`` that prints nothing (:func:`quiet_shutdown`)."""


def busy_threads(grace_s: float = 1.0) -> list[str]:
    """Names of the threads (not daemons) still running after ``grace_s`` seconds: a point computing in a
    thread pool, which Python would wait for at exit."""
    others = [t for t in threading.enumerate() if t is not threading.current_thread() and not t.daemon]
    for t in others:
        t.join(grace_s / max(len(others), 1))
    return [t.name for t in others if t.is_alive()]


def exit_now(status: int) -> None:
    """End the process with ``status`` without waiting for threads (after an interruption, when
    :func:`busy_threads` names some: they compute a point nobody will store)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(status)


def worker_signals() -> None:
    """In a pool worker: ignore Ctrl-C (the parent stops the pool) and die quietly on SIGTERM."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
