"""``python -m voroforge``: the same as the ``voroforge`` command."""

import sys

from .cli import entry

sys.exit(entry())
