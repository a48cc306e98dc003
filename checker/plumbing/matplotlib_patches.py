"""Two changes to matplotlib for one step each, restored after.

* :func:`property_lists_unwritten`: while pyplot is imported, the property lists matplotlib
  writes into the help texts of its artists' ``set`` methods and plotting functions
  (``matplotlib.artist.kwdoc``, a search of every setter's docstring for each artist class)
  are left empty. Only those help texts differ (``help(Line2D.set)`` in this process); the
  methods, their signatures and every figure are the same (tests/report/test_plots_import.py).
  A speed trick: docs/benchmarks.md, "What each trick saves".
* :func:`agg_text_recorded`: while a figure is drawn, every string the Agg renderer draws
  (``RendererAgg.draw_text``, after matplotlib's own processing: what the reader sees) is
  recorded, for the tests of the figures' text. Not a speed trick.

Measured on matplotlib 3.8 to 3.11 (:data:`MEASURED_ON`). :func:`missing_targets` names what a
matplotlib release no longer has; tests/plumbing/test_patch_targets.py fails on it, loudly,
instead of a silent slowdown or figures without their recorded text.
"""

from __future__ import annotations

import inspect
from collections.abc import Iterator
from contextlib import contextmanager

from . import swapped

MEASURED_ON = "matplotlib 3.8 to 3.11 (timed on 3.11.2)"
"""The releases these patches were measured on."""

AGG_DRAW_TEXT_PARAMETERS = ("self", "gc", "x", "y", "s", "prop", "angle", "ismath", "mtext")
"""``RendererAgg.draw_text``'s parameters as the recording wrapper passes them on."""


def missing_targets() -> list[str]:
    """What these patches replace and the installed matplotlib does not have (empty: all)."""
    import matplotlib.artist as artist
    from matplotlib.backends.backend_agg import RendererAgg

    out = []
    if not callable(getattr(artist, "kwdoc", None)):
        out.append("matplotlib.artist.kwdoc")
    draw_text = getattr(RendererAgg, "draw_text", None)
    if draw_text is None:
        out.append("RendererAgg.draw_text")
    elif tuple(inspect.signature(draw_text).parameters) != AGG_DRAW_TEXT_PARAMETERS:
        out.append("RendererAgg.draw_text"
                   f"{tuple(inspect.signature(draw_text).parameters)!r}")
    return out


@contextmanager
def property_lists_unwritten() -> Iterator[None]:
    """``matplotlib.artist.kwdoc`` answers an empty text while inside (pyplot's import);
    where matplotlib has no such function, nothing changes."""
    import matplotlib.artist as artist

    if not hasattr(artist, "kwdoc"):
        yield
        return
    with swapped.attribute(artist, "kwdoc", lambda _artist: ""):
        yield


@contextmanager
def agg_text_recorded(drawn: list[str]) -> Iterator[None]:
    """Every string the Agg renderer draws while inside appended to ``drawn``."""
    from matplotlib.backends.backend_agg import RendererAgg

    orig = RendererAgg.draw_text

    def draw_text(self, gc, x, y, s, prop, angle, ismath=False, mtext=None):
        drawn.append(s)
        return orig(self, gc, x, y, s, prop, angle, ismath, mtext)

    with swapped.attribute(RendererAgg, "draw_text", draw_text):
        yield
