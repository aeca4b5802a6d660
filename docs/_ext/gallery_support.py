"""sphinx-gallery support: which folders are sections, and ``__file__`` for the examples.

Section headers. sphinx-gallery also takes ``README.md`` as the header of a gallery
section once ``.md`` is a source suffix (myst-parser). ``examples/data/README.md`` is the
provenance of the example data, not a gallery section, and rendered as reStructuredText it
has no title. :func:`setup` limits the header names to reStructuredText and text, so
``examples/data/`` stays out of the gallery while its README stays Markdown for GitHub.

``__file__``. sphinx-gallery runs an example without ``__file__`` in its globals, but the
examples find their data next to themselves (``Path(__file__).parent / "data"``), as
scripts run from anywhere must. :func:`example_file`, a ``reset_modules`` hook, sets
``builtins.__file__`` to the example's path while it runs (a name missing from a module's
globals is looked up in builtins) and removes it afterwards.

Warnings. A warning an example raises is printed into its page; Python's format would put
the build machine's absolute path of the raising module in front of it.
"""

from __future__ import annotations

import builtins
import warnings
from pathlib import Path

import sphinx_gallery.gen_rst as _gen_rst

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _rst_headers(gallery_conf):
    for ext in (".txt", ".rst"):
        for name in ("GALLERY_HEADER", "README", "readme"):
            yield name + ext


def example_file(gallery_conf, fname, when):
    """``reset_modules`` hook: ``__file__`` of the example ``fname`` while it runs, and
    warnings printed without the file that raised them (:func:`short_warning`)."""
    if when == "before":
        builtins.__file__ = str(EXAMPLES / Path(fname).name)
        warnings.formatwarning = short_warning
    else:
        builtins.__dict__.pop("__file__", None)
        warnings.formatwarning = _FORMATWARNING


_FORMATWARNING = warnings.formatwarning


def short_warning(message, category, filename, lineno, line=None) -> str:
    """A warning as a reader of the gallery needs it: its kind and its message. Python's
    own format starts with the raising file's path, the build machine's absolute one."""
    return f"{category.__name__}: {message}\n"


def setup(app):
    _gen_rst.iter_gallery_header_filenames = _rst_headers
    return {"parallel_read_safe": True, "parallel_write_safe": True}
