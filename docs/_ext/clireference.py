"""``.. cli-reference::``: every ``rubbercontact`` command's ``--help``, read at build time.

Walks the typer app (:data:`rubbercontact.cli.app`) as a click command tree and renders one
section per command with its help text as a literal block, so the page follows the code.
"""

from __future__ import annotations

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

WIDTH = 88


def _commands():
    import typer

    from rubbercontact.cli import app

    root = typer.main.get_command(app)

    def walk(cmd, path, parent=None):
        # typer may vendor its own click: use the command's classes, test by behaviour
        ctx = cmd.context_class(cmd, info_name=path[-1], parent=parent,
                                terminal_width=WIDTH, max_content_width=WIDTH)
        yield " ".join(path), cmd.get_help(ctx)
        if hasattr(cmd, "list_commands"):
            for name in cmd.list_commands(ctx):
                yield from walk(cmd.get_command(ctx, name), [*path, name], ctx)

    yield from walk(root, ["rubbercontact"])


class CliReference(SphinxDirective):
    has_content = False

    def run(self):
        out = []
        for name, text in _commands():
            section = nodes.section(ids=[nodes.make_id("cli " + name)])
            section += nodes.title(text=name)
            section += nodes.literal_block(text, text, language="text")
            out.append(section)
        return out


def setup(app):
    app.add_directive("cli-reference", CliReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
