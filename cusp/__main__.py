"""``python -m cusp``: the ``cusp`` command."""

import sys

from cusp.app.cli import main

sys.exit(main())
