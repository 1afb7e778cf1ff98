"""``ringcontact fem-vtu``: see :mod:`fem_reference.cli`."""
from fem_reference.cli import vtu_main as main  # noqa: F401
