"""Untrusted text (URL values, the law box): shown literally, never run, never turned into links."""

from __future__ import annotations

import time
import urllib.parse
import urllib.request

import pytest
from browser_harness import (
    FAST,
    ROOT,
    app_tracebacks,
    law_box_refusal,
    open_law_box,
    open_tab,
    settled,
    url_message,
)

from app.state import URL_PARAMS

pytestmark = pytest.mark.browser


# ----------------------------------------------------------------------------- user text
#: OWASP-style payloads (each ≤ 40 characters, so a URL message repeats it whole)
PAYLOADS = [
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(7)>",
    '"><svg onload=alert(1)>',
    "<iframe src=javascript:alert(1)>",
    "<details open ontoggle=alert(1)>",
    "javascript:alert(1)",
    "[x](javascript:alert(1))",
    "';alert(1)//",
    "__import__('os')",
    "**b** _i_ `c` $x$ &amp; # h",
    "<svg onload=alert(1)>",
    "<iframe srcdoc=<svg/onload=alert(1)>>",
    "<javascript:alert(1)>",
    "&lt;img src=x onerror=alert(1)&gt;",
    "&#60;svg onload=alert(1)&#62;",
    "</textarea><script>alert(1)</script>",
    '" onmouseover="alert(1)',
    "' autofocus onfocus='alert(1)",
    "`${alert(1)}`{{7*7}}",
    "\u200b<img src=x onerror=alert(1)>",
    "\u202e<svg onload=alert(1)>",
    # percent-encoded text (on the wire: double-encoded), decoded once by the server only
    "%3Cscript%3Ealert(1)%3C%2Fscript%3E",
    "%253Csvg%2520onload%253Dalert(1)%253E",
    # Markdown's linkify made links of these
    "http://evil.example //evil.example",
]
#: a 5000-character value (a URL message repeats its first 12 characters; a text box takes
#: at most 5000, Panel's TextInput.max_length)
LONG_PAYLOAD = ("<img src=x onerror=alert(1)>" * 179)[:5000]
# every URL parameter but the atlas store, whose value is a path (any text below the server's
# directory is a valid one): it gets its own loop below
URL_NAMES = ("a", "b", "law", "w_plus", "V", "mode", "tab", "N", "tol", "hold", "fig", "sim", "run")

#: every element of the page, through Bokeh's shadow roots: injected markup (an element whose
#: attribute is an event handler, a javascript: URL or a payload's link, or a script that
#: calls alert)
JS_INJECTED = """() => { const bad = []; const walk = (root) => {
  for (const el of root.querySelectorAll('*')) {
    for (const at of el.attributes) {
      const v = (at.value || '').toLowerCase();
      if (at.name.startsWith('on') || v.includes('javascript:') || v.includes('alert(') ||
          v.includes('evil.example'))
        bad.push(el.tagName + ' ' + at.name + '=' + at.value);
    }
    if (el.tagName === 'SCRIPT' && (el.textContent || '').includes('alert(')) bad.push('SCRIPT');
    if (el.shadowRoot) walk(el.shadowRoot);
  } }; walk(document); return bad; }"""


def injected(page) -> list[str]:
    return page.evaluate(JS_INJECTED)


def test_the_payload_list_covers_every_url_parameter():
    assert set(URL_NAMES) | {"atlas"} == set(URL_PARAMS)


def test_user_text_is_shown_literally_and_never_runs(page):
    """Every URL parameter and every text input gets the payload list: no dialog fires, no
    element with an event handler / javascript: URL appears in the DOM, and the messages repeat
    each value exactly as typed (the old Markdown rendering ran ``V`` and ``tab`` payloads as
    script and showed ``__import__('os')`` as ``import('os')``)."""
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    for payload in PAYLOADS:
        q = urllib.parse.urlencode({n: payload for n in URL_NAMES})
        page.goto(f"{page.server}/main?{q}")
        page.locator(".url-message").get_by_text("tab=").wait_for()
        settled(page)
        page.wait_for_timeout(300)  # an onerror fires once the image has failed to load
        # the law's refusal may follow the page (a law the worker has not answered within
        # URL_LAW_WAIT_S is named once it has): bounded wait for every name
        t_end = time.monotonic() + 20
        note = ""
        while time.monotonic() < t_end:
            note = " ".join(url_message(page).split())
            if all(f"{name}=" in note for name in URL_NAMES):
                break
            page.wait_for_timeout(100)
        for name in URL_NAMES:
            assert f"{name}={payload!r}" in note, (name, payload, note)
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the law box: the typed text is named in the editor's refusal, the previous law stays
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    box = open_law_box(page)
    refusal = ""
    for payload in PAYLOADS:
        box.fill(payload)
        box.press("Enter")
        refusal = law_box_refusal(page, refusal)
        assert "law refused" in refusal, (payload, refusal)
        _, _, q = settled(page)
        assert q.get("law") != payload.strip(), (payload, q)  # never applied
        page.wait_for_timeout(300)
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the atlas store from the URL: the scene's message names the path, nothing runs
    for payload in PAYLOADS:
        q = urllib.parse.urlencode({"tab": "atlas", "atlas": payload, "N": "120"})
        page.goto(f"{page.server}/main?{q}")
        msg = page.locator(".scene-atlas .scene-message").get_by_text("no atlas store")
        msg.wait_for(timeout=20_000)
        page.wait_for_timeout(300)
        if "/" not in payload:  # a path keeps its text (a slash may be normalised away)
            assert payload in msg.inner_text(), (payload, msg.inner_text())
        assert not injected(page), (payload, injected(page))
        assert not dialogs, (payload, dialogs)
    # the atlas store's path box: its message names the path as typed
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    open_tab(page, "Atlas")
    store = page.locator(".scene-atlas .bk-input-group", has_text="atlas store").locator("input")
    for payload in [p for p in PAYLOADS if "/" not in p]:
        store.fill(payload)
        store.press("Enter")
        page.locator(".scene-atlas .scene-message").get_by_text(payload).wait_for(timeout=20_000)
        page.wait_for_timeout(300)
        assert not injected(page), (payload, injected(page))
    store.fill(LONG_PAYLOAD)
    store.press("Enter")
    message = page.locator(".scene-atlas .scene-message")
    message.get_by_text(f"atlas store={LONG_PAYLOAD[:12] + '…'!r}").wait_for(timeout=20_000)
    assert not injected(page), injected(page)
    assert not dialogs, dialogs
    assert not app_tracebacks()


def test_a_5000_character_value_is_cut_in_its_message_and_never_runs(page):
    """LONG_PAYLOAD in each URL parameter alone and in the law box: the URL message names the
    parameter with the value's first 12 characters, the law box's text is the law shown in the
    parameters line, nothing runs and the server logs no traceback."""
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    for name in URL_PARAMS:
        page.goto(f"{page.server}/main?" + urllib.parse.urlencode({name: LONG_PAYLOAD}))
        page.locator(".url-message").get_by_text(f"{name}=").wait_for()
        settled(page)
        page.wait_for_timeout(300)
        note = " ".join(url_message(page).split())
        assert f"{name}={LONG_PAYLOAD[:12] + '…'!r}" in note, (name, note)
        assert not injected(page), (name, injected(page))
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    box = open_law_box(page)
    box.fill(LONG_PAYLOAD)
    box.press("Enter")
    refusal = law_box_refusal(page)
    assert "law refused" in refusal and len(refusal) < 2000, refusal[:300]
    page.wait_for_timeout(300)
    assert not injected(page), injected(page)
    assert not dialogs, dialogs
    assert not app_tracebacks()


# ----------------------------------------------------------------------------- math
#: TeX that MathJax (BokehJS's Markup models) typesets: \href/\url make <a href="javascript:…">
#: links, \htmlClass/\class/\style set attributes, \unicode raw code points; every delimiter
#: pair.  Each ≤ 40 characters: a URL message repeats it whole.
MATH_PAYLOADS = [
    r"$$\href{javascript:alert(1)}{pwn}$$",
    r"\(\href{javascript:alert(2)}{pwn}\)",
    r"\[\url{javascript:alert(3)}\]",
    r"$\href{javascript:alert(4)}{p}$",
    r"$$\htmlClass{x}{\href{javascript:5}{}}$$",
    r"\(\class{x}{y}\unicode{x3C}\)",
    r"\[\style{color:red}{\url{javascript:}}\]",
    r"\begin{x}\href{javascript:6}{e}\end{x}",
]
#: the reported link: the Atlas scene's message named the store, and MathJax made
#: "Open the atlas store" a javascript: link (one click ran the alert)
ISSUE_STORE = r"\(\href{javascript:alert(document.domain)}{\text{Open the atlas store}}\)"

#: every <a> of the page (HTML or SVG, through Bokeh's shadow roots): its href and its box
JS_LINKS = """() => { const out = []; const walk = (root) => {
  for (const el of root.querySelectorAll('*')) {
    if (el.localName === 'a') { const r = el.getBoundingClientRect();
      out.push({href: el.getAttribute('href') || el.getAttribute('xlink:href') || '',
                x: r.x + r.width / 2, y: r.y + r.height / 2, w: r.width, h: r.height}); }
    if (el.shadowRoot) walk(el.shadowRoot);
  } }; walk(document); return out; }"""
#: typeset math anywhere in the page (MathJax's SVG output)
JS_TYPESET = """() => { let n = 0; const walk = (root) => {
  for (const el of root.querySelectorAll('*')) {
    if (el.localName === 'mjx-container' || el.hasAttribute('data-mml-node')) n++;
    if (el.shadowRoot) walk(el.shadowRoot);
  } }; walk(document); return n; }"""


#: a link to another page is clicked but not followed (the page and its state stay for the next
#: click); any other link — a javascript: one — does what a click does
JS_STAY = """() => { if (window.__stay) return; window.__stay = true;
  window.addEventListener('click', (e) => {
    const a = e.composedPath().find((n) => n.localName === 'a');
    const href = a && (a.getAttribute('href') || a.getAttribute('xlink:href') || '');
    if (a && !href.trim().toLowerCase().startsWith('javascript:')) e.preventDefault();
  }, true); }"""


def click_every_link(page) -> list[str]:
    """Click, with the mouse where it is, every link of the page; the hrefs seen."""
    page.evaluate(JS_STAY)
    links = page.evaluate(JS_LINKS)
    for link in links:
        if link["w"] > 0 and link["h"] > 0:
            page.mouse.click(link["x"], link["y"])
    page.wait_for_timeout(300)
    return [link["href"] for link in links]


def test_math_in_user_text_is_never_typeset_and_no_link_runs(page):
    """Every math payload in every URL parameter, as the store of an Atlas link (the reported
    link among them) and typed as the law: the page shows it as typed, typesets no math, has
    no javascript: link, and clicking every link of the page fires no dialog.  On 3d9d876 the
    Atlas message typeset the store's name and the click ran alert(document.domain)."""
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    for payload in MATH_PAYLOADS:
        q = urllib.parse.urlencode({n: payload for n in URL_NAMES})
        page.goto(f"{page.server}/main?{q}")
        page.locator(".url-message").get_by_text("tab=").wait_for()
        settled(page)
        note = " ".join(url_message(page).split())
        for name in ("a", "tab", "mode", "fig", "hold"):
            assert f"{name}={payload!r}" in note, (name, payload, note)
        hrefs = click_every_link(page)
        assert not dialogs, (payload, dialogs)  # a click ran script (3d9d876: alert(1))
        assert not [h for h in hrefs if "javascript:" in h.lower()], (payload, hrefs)
        assert not page.evaluate(JS_TYPESET), payload
        assert not injected(page), (payload, injected(page))
    for payload in [*MATH_PAYLOADS, ISSUE_STORE]:
        q = urllib.parse.urlencode({"tab": "atlas", "atlas": payload, "N": "120"})
        page.goto(f"{page.server}/main?{q}")
        msg = page.locator(".scene-atlas .scene-message").get_by_text("no atlas store")
        msg.wait_for(timeout=20_000)
        page.wait_for_timeout(300)
        # named relative to the server's data directory, as typed
        assert f"no atlas store at {payload}" in msg.inner_text(), msg.inner_text()
        hrefs = click_every_link(page)
        assert not dialogs, (payload, dialogs)  # a click ran script (3d9d876: alert(1))
        assert not [h for h in hrefs if "javascript:" in h.lower()], (payload, hrefs)
        assert not page.evaluate(JS_TYPESET), payload
        assert not injected(page), (payload, injected(page))
    page.goto(f"{page.server}/main?{FAST}")
    settled(page)
    box = open_law_box(page)
    refusal = ""
    for payload in MATH_PAYLOADS:
        box.fill(payload)
        box.press("Enter")
        refusal = law_box_refusal(page, refusal)
        assert "law refused" in refusal, (payload, refusal)
        hrefs = click_every_link(page)
        assert not dialogs, (payload, dialogs)  # a click ran script (3d9d876: alert(1))
        assert not [h for h in hrefs if "javascript:" in h.lower()], (payload, hrefs)
        assert not page.evaluate(JS_TYPESET), payload
        assert not injected(page), (payload, injected(page))
    assert not app_tracebacks()


def test_an_atlas_message_names_no_path_of_the_server(page):
    """The Atlas scene's message names a missing store relative to the server's data
    directory (the browser tests' server: the checkout), never by the absolute path."""
    page.goto(
        f"{page.server}/main?" + urllib.parse.urlencode({"tab": "atlas", "atlas": "x/none.zarr"})
    )
    msg = page.locator(".scene-atlas .scene-message").get_by_text("no atlas store")
    msg.wait_for(timeout=20_000)
    assert "no atlas store at x/none.zarr" in msg.inner_text(), msg.inner_text()
    assert str(ROOT) not in page.content()  # the page (its document) has no server path
    assert str(ROOT) not in msg.inner_text()


# ----------------------------------------------------------------------------- CSP
def _directives(header: str) -> dict[str, list[str]]:
    out = {}
    for part in header.split(";"):
        words = part.split()
        if words:
            out[words[0]] = words[1:]
    return out


def test_every_page_is_sent_with_a_content_security_policy(page):
    """The page's Content-Security-Policy allows scripts from the server and the page's own
    (nonce-marked) inline scripts only: no 'unsafe-inline', so neither an injected inline
    handler nor a javascript: link runs, even when put into the page by script (the browser
    refuses them and says so on the console)."""
    response = page.goto(f"{page.server}/main?{FAST}")
    header = response.headers.get("content-security-policy", "")
    d = _directives(header)
    script = d.get("script-src", [])
    assert "'self'" in script and any(w.startswith("'nonce-") for w in script), header
    assert "'unsafe-inline'" not in script and "'strict-dynamic'" not in script, header
    assert d.get("object-src") == ["'none'"] and d.get("base-uri") == ["'self'"], header
    assert d.get("frame-ancestors") == ["'self'"], header
    nonce = next(w for w in script if w.startswith("'nonce-"))[7:-1]
    with urllib.request.urlopen(f"{page.server}/main?{FAST}") as r:  # a fresh nonce each time
        assert nonce not in r.headers["Content-Security-Policy"]
    settled(page)
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    page.evaluate(
        """() => { const a = document.createElement('a'); a.id = 'csp-probe';
        a.href = 'javascript:alert("csp-link")'; a.textContent = 'probe';
        a.style = 'position:fixed;left:5px;top:5px;z-index:99999;font-size:30px';
        document.body.appendChild(a);
        const img = document.createElement('img'); img.setAttribute('onerror', 'alert("csp-img")');
        img.src = 'data:,'; document.body.appendChild(img);
        const div = document.createElement('div');
        div.innerHTML = '<svg onload="alert(1)"></svg>';
        document.body.appendChild(div); }"""
    )
    page.locator("#csp-probe").click()
    page.wait_for_timeout(500)
    assert not dialogs, dialogs
    refused = [e for e in page.js_errors if "Content Security Policy" in e]
    assert refused, page.js_errors  # the browser refused them (and said so)
    page.js_errors[:] = [e for e in page.js_errors if e not in refused]
