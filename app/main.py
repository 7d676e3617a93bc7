"""Entry point: ``panel serve app/main.py`` (see the README for the full serve command)."""

import os

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
explorer.template().servable()
