"""The ``blockdae-api`` directive: the reference of every name in ``blockdae.__all__``,
generated from the docstrings, so that a name added to the top level appears without an
edit here. ``.. blockdae-api:: classes`` (or ``functions``, ``errors``, ``data``) documents
the names of that kind in the order of ``__all__``; ``.. blockdae-api:: summary`` is a
table of them all."""

import inspect
import re

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

KINDS = ("summary", "models", "classes", "functions", "errors", "data")


def kind_of(name, value):
    """Which section of the reference documents ``value`` (``blockdae.<name>``)."""
    import blockdae

    if inspect.isclass(value) and issubclass(value, BaseException):
        return "errors"
    if inspect.isclass(value) and issubclass(value, blockdae.AbstractHybridModel):
        return "models"
    if inspect.isclass(value):
        return "classes"
    if callable(value):
        return "functions"
    return "data"


def public_names():
    """(name, value) of every name in ``blockdae.__all__``, in its order."""
    import blockdae

    return [(name, getattr(blockdae, name)) for name in blockdae.__all__]


def _autodoc_lines(name, kind):
    directive = {"models": "autoclass", "classes": "autoclass", "errors": "autoexception",
                 "functions": "autofunction", "data": "autodata"}[kind]
    lines = [f".. {directive}:: blockdae.{name}"]
    if kind == "data":
        lines.append("   :annotation:")
    return lines + [""]


class BlockdaeApi(SphinxDirective):
    required_arguments = 1

    def run(self):
        kind = self.arguments[0]
        if kind not in KINDS:
            raise self.error(f"blockdae-api: kind must be one of {KINDS}, not {kind!r}")
        names = public_names()
        if kind == "summary":
            lines = [".. autosummary::", "   :nosignatures:", ""]
            lines += [f"   blockdae.{name}" for name, _ in names]
        else:
            lines = [line for name, value in names if kind_of(name, value) == kind
                     for line in _autodoc_lines(name, kind)]
        container = nodes.container()
        nested_parse_with_titles(self.state, StringList(lines, source=self.get_source_info()[0]), container)
        return container.children


LITERAL = re.compile(r"(``.+?``)")
KEYWORDS = re.compile(r"(?<![\\*])\*\*(?=[A-Za-z_])")


def _plain_text(part):
    """``part`` (outside inline literals) with the marks plain text uses escaped: |x| for a
    magnitude, which reStructuredText reads as a substitution, and an unpaired **name
    (``backend, **options:``), which it reads as the start of bold text."""
    part = part.replace("|", r"\|")
    return KEYWORDS.sub(r"\*\*", part) if part.count("**") % 2 else part


def escape_plain_text(app, what, name, obj, options, lines):
    """Escape, outside ``inline literals``, what plain-text docstrings mean literally."""
    for i, line in enumerate(lines):
        if "|" in line or "**" in line:
            lines[i] = "".join(part if part.startswith("``") else _plain_text(part)
                               for part in LITERAL.split(line))


def skip_top_level_names(app, what, name, obj, skip, options):
    """A subpackage's page leaves out what the top level exports: it is documented once,
    under its top-level name, on the API page."""
    import blockdae

    if what == "module" and any(getattr(blockdae, top, None) is obj for top in blockdae.__all__):
        return True
    return None


def setup(app):
    app.add_directive("blockdae-api", BlockdaeApi)
    app.connect("autodoc-process-docstring", escape_plain_text)
    app.connect("autodoc-skip-member", skip_top_level_names)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
