"""fpu-explorer dashboard (Panel + HoloViews + Bokeh).  Serve with ``panel serve app/main.py``.

state.py (the single state owner) → views/<scene>.py (one thin view per tab) → explorer.py
(sidebar, tabs, URL sync, laziness) → main.py (the servable template).  All numbers come from
fpucore through compute/ (cached, timed).
"""
