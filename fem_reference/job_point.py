"""``ringcontact fem-point``: see :mod:`fem_reference.cli`."""
from fem_reference.cli import point_main as main  # noqa: F401
