"""Run sweeps on a ``dask.distributed`` cluster given by its scheduler address (the ``dask`` extra).

:func:`connect` opens a client for ``--scheduler ADDRESS`` (every sweep command has the option) and
closes it at the end; :func:`sweep.run_sweep` takes the client as its executor. Nothing else
changes: the client process keeps the result store (its lock, its files), the workers compute and
send each point back with their own provenance (:func:`sweep.provenance.worker_stamp`).

Workers must import this suite at the same version (install it on them, e.g. in the image of a
dask-jobqueue or SSH cluster). Each worker loads the compiled loops from its own numba cache
(:mod:`contact.compiled_cache`), compiling once per machine.
"""
from __future__ import annotations

import contextlib
import socket
from typing import Iterator

from contact.errors import InputError

CONNECT_TIMEOUT_S = 10.0


def _client_class():
    try:
        from distributed import Client
    except ImportError:
        raise InputError("scheduler: dask.distributed is not installed; install the dask extra "
                         "(pip install 'ringcontact[dask]')") from None
    return Client


def _reachable(address: str, timeout_s: float) -> None:
    """Fail at once on a refused TCP address (dask's client would retry until its timeout)."""
    rest = address.split("://", 1)[1] if "://" in address else address
    if not (address.startswith("tcp://") or "://" not in address):
        return  # tls://, ucx://, inproc://: left to dask
    host, _, port = rest.rpartition(":")
    if not port.isdigit():
        raise InputError(f"scheduler = {address!r}: expected HOST:PORT, e.g. tcp://10.0.0.5:8786")
    try:
        socket.create_connection((host.strip("[]") or "127.0.0.1", int(port)), timeout=timeout_s).close()
    except OSError as e:
        raise InputError(f"scheduler = {address!r}: no dask scheduler answers there ({type(e).__name__})") from None


@contextlib.contextmanager
def connect(address: str | None, timeout_s: float = CONNECT_TIMEOUT_S) -> Iterator[object | None]:
    """A ``distributed.Client`` on the scheduler at ``address`` (None: yields None, the local pool).

    Raises :class:`~contact.errors.InputError` (one line naming the address) when dask is not
    installed or the scheduler does not answer within ``timeout_s``.
    """
    if address is None:
        yield None
        return
    if not str(address).strip():
        raise InputError("scheduler = '': give the scheduler's address, e.g. tcp://10.0.0.5:8786")
    Client = _client_class()
    _reachable(str(address), timeout_s)
    try:
        client = Client(address, timeout=timeout_s, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as e:
        raise InputError(f"scheduler = {address!r}: no dask scheduler answers there within {timeout_s:g} s "
                         f"({type(e).__name__})") from None
    try:
        yield client
    finally:
        client.close()

