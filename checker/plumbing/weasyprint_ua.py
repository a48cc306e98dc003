"""WeasyPrint's ``HTML`` with a user-agent stylesheet of the caller's.

WeasyPrint lays every document out below its own HTML5 user-agent stylesheet (hundreds of
rules for elements a report never uses); ``HTML._ua_stylesheets`` is the method that gives
it. :func:`html_class` returns a subclass whose method gives the report's own, shorter one
(``templates/report_ua.css``: the defaults of the elements the template uses): the same pages
in less layout time (docs/benchmarks.md, "What each trick saves").

Measured on WeasyPrint 62-70 (:data:`MEASURED_ON`), whose style cascade (``weasyprint.css``)
calls ``html._ua_stylesheets(...)``. :func:`missing_targets` names what a release no longer
has; tests/plumbing/test_patch_targets.py fails on it, loudly: should a release stop calling
the method, the report would silently be laid out under WeasyPrint's own stylesheet.
"""

from __future__ import annotations

import inspect
from typing import Any

MEASURED_ON = "WeasyPrint 62 to 70 (timed on 70.0)"
"""The releases this subclass was measured on."""


def missing_targets(wp: Any) -> list[str]:
    """What the subclass relies on and the installed WeasyPrint does not have (empty: all)."""
    out = []
    if not callable(getattr(wp.HTML, "_ua_stylesheets", None)):
        out.append("weasyprint.HTML._ua_stylesheets")
    elif "._ua_stylesheets(" not in inspect.getsource(wp.css):
        out.append("weasyprint.css calling html._ua_stylesheets")
    return out


def html_class(wp: Any, ua_css: str) -> type:
    """``wp.HTML`` laying documents out below the stylesheet ``ua_css`` (CSS text)."""
    ua = wp.CSS(string=ua_css)

    class HTML(wp.HTML):
        def _ua_stylesheets(self, *args, **kwargs):
            return [ua]

    return HTML
