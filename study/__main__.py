import sys

try:
    from study.cli import main
except KeyboardInterrupt:  # Ctrl-C while the package loads: nothing was started
    print("study: interrupted", file=sys.stderr)
    sys.exit(130)

sys.exit(main())
