"""``ringcontact fem-sweep``: see :mod:`fem_reference.cli`."""
from fem_reference.cli import sweep_main as main  # noqa: F401
