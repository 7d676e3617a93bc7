"""Entry point: ``panel serve app/main.py`` (see the README for the full serve command)."""

import panel as pn

from app.explorer import Explorer, sync_url

pn.extension(loading_indicator=True, notifications=False, throttled=True)

explorer = Explorer()
sync_url(explorer)  # URL parameters override the defaults before the first render
explorer.first_render()
pn.state.onload(explorer.start)
explorer.template().servable()
