"""The Content-Security-Policy of every page the server sends (installed by app/warm.py, the
``--setup`` of ``panel serve``, before the first request; again by app/main.py, idempotent).

A second line behind :mod:`app.views.untrusted`: were user text ever to reach the page as
markup again, the browser still refuses to run it.  The policy (:func:`policy`):

* ``script-src 'self' 'nonce-…' 'unsafe-eval'`` — scripts from this server, and the page's own
  inline scripts, which each carry this response's nonce (Bokeh's page starts the document
  with an inline script; its document JSON is an inline ``application/json`` block).  With a
  nonce, ``'unsafe-inline'`` is absent: an inline event handler (``onerror=…``), a
  ``javascript:`` URL (a link, an iframe, a form action) and any ``<script>`` injected into
  the page do not run.  ``'unsafe-eval'``: BokehJS compiles a ``CustomJS`` callback (the
  "Copy as Python" and paper buttons) with ``new Function``; eval runs only code the server
  sent as such, never page text.
* ``style-src 'self' 'unsafe-inline'`` — Bokeh and Panel set inline styles and constructed
  stylesheets on every component (no script runs from a style).
* ``img-src 'self' data: blob:``, ``font-src 'self' data:`` — icons and fonts Bokeh and
  Panel inline as data URLs; ``connect-src 'self'`` — the session's websocket, this host only;
  ``worker-src 'self' blob:``.
* ``object-src 'none'``, ``base-uri 'self'``, ``form-action 'self'``, ``frame-ancestors
  'self'`` — no plugins, no ``<base>`` redirecting relative URLs, no form posting elsewhere,
  no framing by another site (clickjacking).
"""

from __future__ import annotations

import re
import secrets

from tornado.web import RequestHandler

#: an opening script tag (not ``<scripts``, not a closing tag)
_SCRIPT_TAG = re.compile(rb"<script(?=[\s>])", re.IGNORECASE)


def policy(nonce: str) -> str:
    """The Content-Security-Policy header's value for a page whose inline scripts carry
    ``nonce`` (see the module's docstring for what each directive allows and why)."""
    return "; ".join(
        [
            "default-src 'self'",
            f"script-src 'self' 'nonce-{nonce}' 'unsafe-eval'",
            "style-src 'self' 'unsafe-inline'",
            "img-src 'self' data: blob:",
            "font-src 'self' data:",
            "connect-src 'self'",
            "worker-src 'self' blob:",
            "object-src 'none'",
            "base-uri 'self'",
            "form-action 'self'",
            "frame-ancestors 'self'",
        ]
    )


_tornado_finish = RequestHandler.finish


def _finish_with_policy(self, chunk=None):
    """Tornado's ``finish``; an HTML response not yet flushed first gets a fresh nonce on each
    of its script tags and the policy naming it."""
    html = str(self._headers.get("Content-Type", "")).startswith("text/html")
    if html and not self._finished and not self._headers_written:
        if chunk is not None:
            self.write(chunk)
            chunk = None
        nonce = secrets.token_urlsafe(18)
        body = b"".join(self._write_buffer)
        self._write_buffer = [_SCRIPT_TAG.sub(b'<script nonce="' + nonce.encode() + b'"', body)]
        self.set_header("Content-Security-Policy", policy(nonce))
        self.set_header("X-Content-Type-Options", "nosniff")
    return _tornado_finish(self, chunk)


def install_content_security_policy() -> None:
    """Every HTML page of this process's Tornado server (Bokeh's and Panel's pages, error
    pages) is sent with :func:`policy`; idempotent."""
    RequestHandler.finish = _finish_with_policy
