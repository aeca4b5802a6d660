"""Study reports written for the repository root render from ``docs/`` too.

Reports under ``docs/validation/`` are also read on GitHub from the repository root, and
some (those kept verbatim from ``VALIDATION.md``) name their figures and pages by
root-relative paths, ``docs/validation/section3/fig2_law.png``. This rewrites the Markdown
link and image targets ``](docs/...`` of those pages to paths relative to the page, so the
images are found and the links resolve, without changing the files.
"""

from __future__ import annotations


def _rewrite(app, docname, source):
    if not docname.startswith("validation/"):
        return
    up = "../" * docname.count("/")
    source[0] = source[0].replace("](docs/", "](" + up)


def setup(app):
    app.connect("source-read", _rewrite)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
