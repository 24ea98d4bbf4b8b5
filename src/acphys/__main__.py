"""``python -m acphys``: the same as the ``acphys`` command."""

import sys

from acphys.cli import main

sys.exit(main())
