"""``ringcontact fem-check``: see :mod:`fem_reference.cli`."""
from fem_reference.cli import check_main as main  # noqa: F401
