"""Cheap top-level (picklable) task functions shared by the tests of the sweep package."""
import os

import numpy as np

from sweep import Task


def square_task(x: float, calls_dir: str):
    """Cheap deterministic task; records each call in calls_dir (top level: picklable)."""
    n = len(os.listdir(calls_dir))
    with open(os.path.join(calls_dir, f"call-{x:g}-{os.getpid()}-{n}-{os.urandom(4).hex()}"), "w"):
        pass
    return {"x": np.array([x]), "y": np.linspace(0, x, 50) ** 2}, {"sum_y": float(np.sum(np.linspace(0, x, 50) ** 2))}


def failing_task(x: float):
    if x == 2.0:
        raise ValueError("boom at 2")
    return {"x": np.array([x])}, {}


def calls(d, x):
    """How often square_task ran for x."""
    return sum(1 for f in os.listdir(d) if f.startswith(f"call-{x:g}-"))


def square_tasks(calls_dir, xs=(1.0, 2.0, 3.0, 4.0, 5.0)):
    return [Task(f"x{x:g}", square_task, {"x": x, "calls_dir": str(calls_dir)}) for x in xs]


def waiting_task(x: float, calls_dir: str, gate: str, timeout_s: float = 60.0):
    """Marks its start (``start-<x>-<pid>`` in calls_dir), then waits until the file ``gate`` exists."""
    import time

    with open(os.path.join(calls_dir, f"start-{x:g}-{os.getpid()}"), "w"):
        pass
    t0 = time.monotonic()
    while not os.path.exists(gate) and time.monotonic() - t0 < timeout_s:
        time.sleep(0.05)
    return {"x": np.array([x])}, {"pid": os.getpid()}


def dying_task(x: float, calls_dir: str, die_at: float):
    """square_task, except that the first call with x == die_at kills its own process (kill -9)."""
    import signal

    if x == die_at and not os.path.exists(os.path.join(calls_dir, "died")):
        with open(os.path.join(calls_dir, "died"), "w"):
            pass
        os.kill(os.getpid(), signal.SIGKILL)
    return square_task(x, calls_dir)


def alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie does not)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def chain_block(xs: list, calls_dir: str, stored: dict, fail_at: float | None = None) -> dict:
    """A task with several outputs: a running sum over ``xs``, each point's ``total`` its lower neighbour's plus
    its own x, taken from ``stored`` (key -> info) where the neighbour is stored; records each x computed."""
    out, total = {}, 0.0
    for x in xs:
        key = f"c{x:g}"
        if key in stored:
            total = stored[key]["total"]
            continue
        if x == fail_at:
            raise ValueError(f"boom at {x:g}")
        with open(os.path.join(calls_dir, f"call-{x:g}-{os.getpid()}-{os.urandom(4).hex()}"), "w"):
            pass
        total += x
        out[key] = ({"x": np.array([x])}, {"total": total, "neighbour_stored": f"c{xs[xs.index(x) - 1]:g}" in stored})
    return out


def chain_tasks(calls_dir, blocks=((1.0, 2.0, 3.0), (4.0, 5.0)), fail_at=None):
    """One chain_block task per block; outputs ``c<x>`` with params ``{"x": x}``."""
    params = {"calls_dir": str(calls_dir), **({"fail_at": fail_at} if fail_at is not None else {})}
    return [Task(f"block{b[0]:g}-{b[-1]:g}", chain_block, {"xs": list(b), **params},
                 tuple((f"c{x:g}", {"x": x}) for x in b)) for b in blocks]
