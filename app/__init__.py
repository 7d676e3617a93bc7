"""fpu-explorer dashboard (Panel + HoloViews + Bokeh).  Serve with ``panel serve app/main.py``.

state.py (the single state owner) → views/<scene>.py (one thin view per tab); widgets.py (widgets
kept in step with the server) → law_editor.py (the law box and sliders) → explorer.py (sidebar,
tabs, laziness, the template) → url_sync.py (the page from its URL, the URL kept equal to the
state) → main.py (serves it).  All numbers come from fpucore through compute/ (cached, timed).
"""
