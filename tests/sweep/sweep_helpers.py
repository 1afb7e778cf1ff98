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
