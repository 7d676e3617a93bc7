"""Untrusted text shown literally: :func:`md_literal` and the Markdown pane options
(:data:`LITERAL_MD`) that go with it.

User-supplied text (a URL value, a typed law, a store path, an exception message repeating
them) reaches the page through Markdown panes; this is the one place that makes it inert.  Kept
in a file of its own because it is the app's XSS boundary: a reviewer reads it alone.
"""

from __future__ import annotations

import re

#: characters that start inline Markdown anywhere in a line (emphasis, code, links, strike,
#: math, table cells): backslash-escaped (CommonMark escapes any ASCII punctuation)
_MD_INLINE = frozenset("\\`*_[]~$|")
#: characters that would open or close HTML (and attribute values): written as entities
_HTML_CHARS = {"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#x27;"}
#: block markup, only at a line's start: a heading, a list item (-, +, 1.), a setext underline
_MD_BLOCK = re.compile(r"(?m)^([ \t]*)([#+=-])")
_MD_NUMBERED = re.compile(r"(?m)^([ \t]*\d+)([.)])")


#: the options of a Markdown pane that shows md_literal text: no math and no linkify (which
#: turned "evil.com", "//host" or "a@b.co" in a URL value, and "x.py" in a store path, into links)
LITERAL_MD = {"disable_math": True, "renderer_options": {"linkify": False}}


def md_literal(text) -> str:
    """``text`` for a Markdown pane, shown exactly as typed and never as markup.

    User-supplied text (a URL value, a typed law, an exception message repeating them) reaches
    the page through Markdown panes whose renderer passes raw HTML through: ``<img onerror=…>``
    in a URL ran script in the page.  One pass writes the HTML characters as entities and
    backslash-escapes inline Markdown (one pass, so an entity's ``#`` is not escaped again);
    then block markup at a line's start is escaped.  ``__import__('os')`` and ``w**2`` show
    literally, ``[x](…)`` is no link, ``$…$`` no math, and the source stays readable."""
    out = []
    for ch in str(text):
        if ch in _HTML_CHARS:
            out.append(_HTML_CHARS[ch])
        elif ch in _MD_INLINE:
            out.append("\\" + ch)
        else:
            out.append(ch)

    escaped = _MD_BLOCK.sub(r"\1\\\2", "".join(out))
    return _MD_NUMBERED.sub(r"\1\\\2", escaped)  # "1." → "1\." (no list item)
