"""Sphinx configuration of the rubbercontact documentation (``make docs``).

Markdown pages through myst-parser, the API from the numpy-style docstrings through
autodoc + autosummary + numpydoc, and ``examples/*.py`` as a sphinx-gallery. The gallery
runs the examples on their reduced settings (``RUBBERCONTACT_EXAMPLE_QUICK=1``) unless the
variable is set otherwise; ``-D plot_gallery=0`` builds without running them.
"""

import os
import shutil
import sys
from importlib.metadata import version as _version
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

os.environ.setdefault("RUBBERCONTACT_EXAMPLE_QUICK", "1")
os.environ.setdefault("MPLBACKEND", "Agg")

project = "rubbercontact"
author = "rubbercontact developers"
copyright = "rubbercontact developers, MIT licence"
release = _version("rubbercontact")
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "configref",
    "clireference",
    "gallery_support",
    "rootpaths",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
templates_path = ["_templates"]
# validation/<case>/report.md are the pieces of VALIDATION.md (included whole by
# validation_report.md), written for the repository root's relative paths.
exclude_patterns = ["_build", "validation/reference-cache/**", "validation/*/report.md",
                    # included verbatim by findings.md and the README, not a page
                    "validation/headline.md",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.json"]

# -- Markdown ---------------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# -- API ----------------------------------------------------------------------------------
# autosummary writes the API pages into the source tree and never deletes one whose name has
# left an __all__: start from none, so a stale page cannot fail the build.
shutil.rmtree(Path(__file__).parent / "api" / "generated", ignore_errors=True)
autosummary_generate = True
autosummary_ignore_module_all = False      # a module's public names are its __all__
autodoc_default_options = {"members": False}
autodoc_typehints = "none"                 # numpydoc shows the documented types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
add_module_names = False

intersphinx_mapping = {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable", None),
    "xarray": ("https://docs.xarray.dev/en/stable", None),
}
# Offline builds (CI, the docs test) have no inventories to fetch: intersphinx then only
# leaves references to those projects unlinked.
if os.environ.get("RUBBERCONTACT_DOCS_OFFLINE", "1") == "1":
    intersphinx_mapping = {}

# -- Gallery ------------------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"make_dma_synthetic\.py",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "show_memory": False,
    # gallery_support.example_file gives each example its __file__ (its data lie beside it)
    "reset_modules": ("matplotlib", "gallery_support.example_file"),
    "reset_modules_order": "both",
}

# -- HTML ---------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"rubbercontact {release}"
html_static_path = []
