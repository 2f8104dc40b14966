"""``python -m psdbound`` entry point."""

import sys

from psdbound.cli import main

if __name__ == "__main__":
    sys.exit(main())
