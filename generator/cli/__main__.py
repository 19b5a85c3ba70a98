"""``python -m xacrokit.cli``: the same as ``gen-robot``."""

import sys

from .app import main

sys.exit(main())
