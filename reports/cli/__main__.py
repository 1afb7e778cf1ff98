"""``python -m reports.cli JOB ...``: the same dispatcher as the ``ringcontact`` command."""
import sys

from reports.cli import main

sys.exit(main())
