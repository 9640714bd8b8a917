"""``python -m study``: the same entry as the ``study`` console script (:mod:`study.console`)."""

import sys

from study.console import main

sys.exit(main())
