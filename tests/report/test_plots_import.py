"""checker.report.plots.pyplot: matplotlib imported with its help texts' property lists left
empty works as matplotlib does and draws the same figures."""

from tests.helpers import example_path, fresh_python

DRAW_ALL = """
import hashlib, sys
from checker import api
from checker.report import plots, sections
{setup}
res = api.check({path!r})
sections.load_sections()
plots.DEFERRED = []
for m in sections.modules_with_sections(res):
    sections.SECTIONS[m](res)
images = [plots.draw_deferred(i) for i in range(len(plots.DEFERRED))]
print(len(images), hashlib.md5(b"".join(images)).hexdigest())
"""


def test_matplotlib_works_as_without_the_shortcut():
    out = fresh_python("""
from checker.report import plots
plt = plots.pyplot()
import inspect
import matplotlib.artist
from matplotlib.lines import Line2D
print(len(matplotlib.artist.kwdoc(Line2D)) > 1000,
      "color" in inspect.signature(Line2D.set).parameters)
line, = plt.plot([0, 1], [1, 2])
plt.setp(line, color="red", linewidth=2)
print(line.get_color(), line.get_linewidth(), plt.getp(line, "color"))
""")
    assert out.splitlines() == ["True True", "red 2.0 red"]


def test_every_figure_of_the_i4_report_the_same_as_with_matplotlibs_own_import(tmp_path):
    path = str(example_path(tmp_path))
    ours = fresh_python(DRAW_ALL.format(setup="", path=path))
    own = fresh_python(DRAW_ALL.format(
        setup="import contextlib\nfrom checker.plumbing import matplotlib_patches as mp\n"
              "mp.property_lists_unwritten = contextlib.nullcontext",
        path=path))
    assert int(ours.split()[0]) > 15
    assert ours == own
