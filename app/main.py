"""Entry point: ``panel serve app/main.py`` (see the README for the full serve command)."""

import os
import sys

# Panel's Location parses every URL value itself; Python's int-string limit (4300 digits) made a
# 5000-digit value a traceback there.  The app's own parser refuses values > 40 characters.
sys.set_int_max_str_digits(0)

# Components created later in worker threads must link Panel's CSS from this server, not from
# cdn.holoviz.org (the page must work offline and without console errors).
os.environ.setdefault("BOKEH_RESOURCES", "server")

import panel as pn  # noqa: E402

from app.explorer import from_url  # noqa: E402
from app.resources import serve_locally  # noqa: E402

serve_locally()

pn.extension(loading_indicator=True, notifications=False, throttled=True)

explorer = from_url()  # the validated URL parameters, before the first render
explorer.first_render()
pn.state.onload(explorer.start)
# One recompute of the document's model graph instead of one per template root (~20, each
# walking ~1400 models): the session's page was built in 2.7 s, now 0.7 s.
with pn.state.curdoc.models.freeze():
    explorer.template().servable()
