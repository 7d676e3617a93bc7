"""Entry point: ``panel serve app/main.py`` (see the README for the full serve command)."""

import os

# Components created later in worker threads must link Panel's CSS from this server, not from
# cdn.holoviz.org (the page must work offline and without console errors).
os.environ.setdefault("BOKEH_RESOURCES", "server")

import panel as pn  # noqa: E402

from app import compute  # noqa: E402
from app.resources import serve_locally  # noqa: E402
from app.server_guards import (  # noqa: E402
    schedule_callbacks_in_order,
    serve_document_locally,
    tolerate_detached_sessions,
    tolerate_long_url_values,
)
from app.url_sync import from_url  # noqa: E402

serve_locally()
serve_document_locally(pn.state.curdoc)
tolerate_long_url_values()
tolerate_detached_sessions()
schedule_callbacks_in_order()

pn.extension(loading_indicator=True, notifications=False, throttled=True)

with compute.building_page():  # on the event loop: a law being built is not waited for
    explorer = from_url()  # the validated URL parameters, before the first render
    explorer.first_render()
pn.state.onload(explorer.start)
# One recompute of the document's model graph instead of one per template root (~20, each
# walking ~1400 models): the session's page was built in 2.7 s, now 0.7 s.
with pn.state.curdoc.models.freeze():
    explorer.servable()
