r"""Untrusted text shown literally: :func:`md_literal`, and the panes that show it
(:class:`LiteralMarkdown`, :class:`LiteralAlert`: no math, no linkify).

User-supplied text (a URL value, a typed law, a store path, an exception message repeating
them) reaches the page through Markdown panes; this is the one place that makes it inert.  Kept
in a file of its own because it is the app's XSS boundary: a reviewer reads it alone.

Math: Panel 1.9's Markdown pane does not send its ``disable_math`` to the browser (its
``_rename`` drops it, and its own parser ignores it), so BokehJS's Markup model rendered every
``$$…$$``, ``\(…\)`` or ``\[…\]`` in the shown text with MathJax — and MathJax's ``\href``
makes an ``<a href="javascript:…">``: one click on a link's message ran script.  The panes
here send ``disable_math=True`` to the model, so no text of theirs is ever typeset.  The app
shows no math anywhere, so every Markdown and Alert pane of app/ is one of these
(tests/app/test_app_untrusted.py checks the whole page's models).
"""

from __future__ import annotations

import html
import re

import panel as pn
import param

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


_NO_MATH = "Always True: sent to the browser's Markup model (Panel's Markdown drops it)."


class LiteralMarkdown(pn.pane.Markdown):
    """A Markdown pane whose text is never typeset as math (in the browser: the model's
    ``disable_math``) nor linkified.  Every Markdown pane of the app is one."""

    disable_math = param.Boolean(default=True, constant=True, doc=_NO_MATH)

    renderer_options = param.Dict(default={"linkify": False}, nested_refs=True)

    _rename = {"disable_math": "disable_math"}


class LiteralAlert(pn.pane.Alert):
    """An Alert pane (a message) whose text is never typeset as math nor linkified."""

    disable_math = param.Boolean(default=True, constant=True, doc=_NO_MATH)

    renderer_options = param.Dict(default={"linkify": False}, nested_refs=True)

    _rename = {"disable_math": "disable_math"}


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


_TAG = re.compile(r"<[^>]*>")
_BACKTICKS = re.compile(r"`+")


def md_plain(markdown: str) -> str:
    """What a :class:`LiteralMarkdown` pane shows for ``markdown``, as plain text (the words on
    screen: markup gone, md_literal's escapes undone) — for files that must not render it
    again (a notebook's Markdown cell is typeset by Jupyter's MathJax)."""
    rendered = html.unescape(LiteralMarkdown()._transform_object(markdown)["object"])
    text = html.unescape(_TAG.sub("", rendered))  # md_literal wrote user "<" as an entity
    return "\n".join(line.rstrip() for line in text.strip().splitlines())


def md_code_block(text: str) -> str:
    """``text`` as a fenced code block: shown verbatim by any Markdown renderer, never math
    (Jupyter's and MathJax's math finders skip code), and no fence inside it closes it."""
    longest = max((len(m) for m in _BACKTICKS.findall(text)), default=0)
    fence = "`" * max(3, longest + 1)
    return f"{fence}text\n{text}\n{fence}"
