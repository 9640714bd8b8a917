"""The ``study`` console script and ``python -m study``: a Ctrl-C at any moment ends with one line, never a traceback.

This module imports nothing but the standard library before it installs its SIGINT handler, so it covers the
seconds of importing numpy, pint and the solvers (``study.cli``); while a command runs, Ctrl-C is the command's
(a sweep says what it kept, exit status 130); once the command has returned, a Ctrl-C during the interpreter's exit
(closing files, dask's exit handlers) is one line and exit status 130 too. Only a SIGINT in the milliseconds before
Python runs this module (``study/__init__.py`` sets three environment variables) is Python's own.
"""

from __future__ import annotations

import os
import signal
import sys

STARTING = "study: interrupted while starting: nothing new was computed"
EXITING = "study: interrupted while exiting: the command had ended; what it reported above stands"


def _stop_with(line: str):
    """A SIGINT handler that prints ``line`` on stderr and ends the process now with status 130: a half-imported
    package, or one already shutting down, must not run more of its code (or its exit handlers' tracebacks)."""

    def stop(signum, frame):
        try:
            sys.stdout.flush()
        except Exception:  # noqa: BLE001 - a closed or broken stdout: the line on stderr is what matters
            pass
        os.write(2, (line + "\n").encode())
        os._exit(130)

    return stop


def main(argv=None) -> int:
    """Run the ``study`` command (:func:`study.cli.main`) with Ctrl-C guarded before, during and after it."""
    signal.signal(signal.SIGINT, _stop_with(STARTING))
    from study.cli import main as run  # the heavy imports: seconds

    signal.signal(signal.SIGINT, signal.default_int_handler)  # the command's own: KeyboardInterrupt
    try:
        code = run(argv)
    except KeyboardInterrupt:  # between the command's own handling and here
        code = 130
        print("study: interrupted", file=sys.stderr)
    signal.signal(signal.SIGINT, _stop_with(EXITING))
    return code


if __name__ == "__main__":
    sys.exit(main())
