"""fpu-explorer dashboard (Panel + HoloViews + Bokeh).  Serve with ``fpu serve`` (panel serve of
main.py with warm.py's warm-up); installed from the wheel as ``fpu_explorer_app``, so every
import inside this package is relative.

state.py (the single state owner) → views/<scene>.py (one thin view per tab); widgets.py (widgets
kept in step with the server) → law_editor.py (the law box and sliders) → explorer.py (sidebar,
tabs, laziness, the template) → url_sync.py (the page from its URL, the URL kept equal to the
state) → page.py (one session's page) → main.py (the file Panel serves).  All numbers come
from fpucore through compute/ (cached, timed).
"""
