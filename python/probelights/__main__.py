"""python -m probelights: the same as the `probelights` command."""

import sys

from ._command import main

sys.exit(main())
