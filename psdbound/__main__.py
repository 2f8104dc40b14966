"""``python -m psdbound`` entry point."""

from psdbound.cli.main import console

if __name__ == "__main__":
    console()
