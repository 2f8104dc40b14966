"""Headless Chromium for the tests that look at a page as a person does."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

#: Skip a test when the browser or the PDF rasteriser is missing (.ci/run installs both).
needs_browser = pytest.mark.skipif(
    shutil.which("chromium") is None or shutil.which("pdftoppm") is None,
    reason="needs Debian's chromium and poppler-utils (installed by .ci/run)",
)

_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def chromium(page: Path, profile: Path, *args: str) -> str:
    """Run headless Chromium on a local page with a fresh profile; return its stdout."""
    cmd = ["chromium", *_FLAGS, f"--user-data-dir={profile}", *args, page.as_uri()]
    return subprocess.run(cmd, capture_output=True, timeout=120, check=True, text=True).stdout


def not_blank(png: Path) -> float:
    """Standard deviation of an image's RGB values (0: a blank image)."""
    import matplotlib.image as mpimg

    img = mpimg.imread(png)
    return float(np.std(img[..., :3]))
