"""``python3 -m wheelsim_post``: the same as the wheelsim-post script."""

import sys

from .cli import main

sys.exit(main())
