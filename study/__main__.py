import os
import sys

try:
    from study.cli import main
except KeyboardInterrupt:  # Ctrl-C while the package loads: nothing was started
    print("study: interrupted", file=sys.stderr, flush=True)
    os._exit(130)  # now: a half-imported package must not run its exit handlers

sys.exit(main())
