import os
import signal
import sys

try:
    from study.cli import main
except KeyboardInterrupt:  # Ctrl-C while the package loads: nothing was started
    print("study: interrupted while starting: nothing new was computed", file=sys.stderr, flush=True)
    os._exit(130)  # now: a half-imported package must not run its exit handlers

code = main()
signal.signal(signal.SIGINT, signal.SIG_IGN)  # the work is done or reported: a Ctrl-C now cannot cut the exit
sys.exit(code)
