"""Gallery section headers are ``GALLERY_HEADER.rst`` (or ``README.rst``/``.txt``) only.

sphinx-gallery also takes ``README.md`` as the header of a gallery section once ``.md`` is a
source suffix (myst-parser). ``examples/data/README.md`` is the provenance of the example
data, not a gallery section, and rendered as reStructuredText it has no title. This limits
the header names to reStructuredText and text, so ``examples/data/`` stays out of the
gallery while its README stays Markdown for GitHub.
"""

from __future__ import annotations

import sphinx_gallery.gen_rst as _gen_rst


def _rst_headers(gallery_conf):
    for ext in (".txt", ".rst"):
        for name in ("GALLERY_HEADER", "README", "readme"):
            yield name + ext


def setup(app):
    _gen_rst.iter_gallery_header_filenames = _rst_headers
    return {"parallel_read_safe": True, "parallel_write_safe": True}
