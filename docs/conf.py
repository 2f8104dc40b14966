"""Sphinx configuration of the psdbound documentation.

Build with ``python -m sphinx -W --keep-going -b html docs docs/_build/html``
(warnings are errors) and run the tutorial with ``python -m sphinx -b doctest
docs docs/_build/doctest``. The build needs no network: intersphinx has no
inventories unless ``PSDBOUND_DOCS_INTERSPHINX=1`` is set.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent))

import psdbound  # noqa: E402

project = "psdbound"
author = "psdbound developers"
copyright = "psdbound developers"  # noqa: A001
version = release = psdbound.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.doctest",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "numpydoc",
    "psdbound_docs",
    "psdbound_architecture",
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
root_doc = "index"
default_role = "literal"
nitpicky = False
smartquotes = False  # keep "--option" and quotes as typed

# -- autodoc / autosummary / numpydoc ----------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"
autodoc_member_order = "bysource"
autodoc_default_options = {"show-inheritance": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False

# -- intersphinx: no network at build time ------------------------------------
# Inventories are only fetched when asked for explicitly (a networked build).
intersphinx_mapping: dict[str, tuple[str, str | None]] = {}
if os.environ.get("PSDBOUND_DOCS_INTERSPHINX") == "1":
    intersphinx_mapping = {
        "python": ("https://docs.python.org/3", None),
        "numpy": ("https://numpy.org/doc/stable", None),
        "scipy": ("https://docs.scipy.org/doc/scipy", None),
    }

# -- doctest ------------------------------------------------------------------
# The tutorial is self-contained (it also runs under plain ``doctest``).
import doctest as _doctest  # noqa: E402

# Only the ``.. doctest::`` blocks of the pages run under ``-b doctest``; the
# ``>>>`` examples of the API docstrings run with their modules under pytest.
doctest_test_doctest_blocks = ""
doctest_default_flags = (
    _doctest.ELLIPSIS | _doctest.NORMALIZE_WHITESPACE | _doctest.IGNORE_EXCEPTION_DETAIL
)

# -- math ---------------------------------------------------------------------
# MathJax is loaded by the reader's browser; the build itself needs no network.
math_number_all = False

# -- HTML ---------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"psdbound {release}"
html_static_path: list[str] = []
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_sidebars = {"**": ["sidebar-nav-bs"]}
html_last_updated_fmt = None
