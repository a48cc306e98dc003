"""Render the report: sections (figures drawn in worker processes) -> jinja2 HTML -> WeasyPrint
PDF with the results workbook attached (deterministic bytes for the same input on the same
day).

:func:`build_report` runs the stages and times them (``Report.stages``, shown by
``benchmarks/bench_report.py``): forked drawing processes build the sections (figures as
placeholders of their size) while this process imports the PDF engine; then the HTML and the
PDF layout, while the drawing processes draw the figures and a forked process writes the
results workbook; then the PDF file, the drawn figures in place of the placeholders.
"""

from __future__ import annotations

import base64
import datetime as _dt
import logging
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from .. import __version__
from ..api import CheckResult
from ..plumbing.forked import ForkedCall
from ..plumbing.resources import templates_dir
from ..results.caveats import estimate_caveat
from . import results_book, review, summary
from .pdf_engine import (
    FIGURE_SCHEME,
    FigureCache,
    PageProgress,
    children_cpu,
    fetcher,
    html_class,
    load_weasyprint,
    write_pdf,
    write_with_figures,
)
from .sections import SECTIONS, SectionJob, modules_with_sections

if TYPE_CHECKING:
    from .pdf_process import PdfEngine


Progress = Callable[[str], None]


def rule_label(name: str, rule_id: str):
    """A rule's name with its id after it, as HTML: the last word of the name and the id are
    kept on one line (``<span class="name-end">``). With the id alone as the inline box that
    does not fit, WeasyPrint broke the name after its first word ("Contact / stress under the
    bolt head JNT-002") instead of before the id."""
    from markupsafe import Markup, escape

    head, _, last = str(name).rpartition(" ")
    return Markup(f"{escape(head)}{' ' if head else ''}<span class=\"name-end\">{escape(last)}"
                  f" <span class=\"rule-id\">{escape(rule_id)}</span></span>")


def _environment():
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape

    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    env.filters["rule_label"] = rule_label
    return env


def _figure_sources(sections: list[dict], figures: dict[str, bytes] | None = None,
                    pending: dict[str, tuple[int, int]] | None = None) -> list[dict]:
    """Figures as JPEG images. With ``figures`` (the PDF), each image is a short
    ``checker-figure:N`` URL served from that dict by :class:`_Fetcher`: the HTML parser then
    never reads the base64 text that data URIs would add; ``pending`` collects the URLs of
    the figures that are placeholders still being drawn (URL -> ``png.key``). Without it
    (the standalone HTML file), data URIs."""
    from .plots import Deferred

    n = 0
    for s in sections:
        for b in s["blocks"]:
            if b["type"] == "figure" and b.get("png"):
                w = getattr(b["png"], "width_mm", None)
                if w is not None and w < 165 and "width_mm" not in b:
                    b["width_mm"] = round(w, 1)  # a narrow figure keeps its size
                data = bytes(b["png"])
                if figures is not None:
                    n += 1
                    figures[f"{FIGURE_SCHEME}{n}"] = data
                    b["src"] = f"{FIGURE_SCHEME}{n}"
                    if isinstance(b["png"], Deferred):
                        if pending is None:
                            raise ValueError("a figure placeholder in a finished report")
                        pending[b["src"]] = b["png"].key
                else:
                    b["src"] = "data:image/jpeg;base64," + base64.b64encode(data).decode(
                        "ascii")
    return sections


def standalone_html(html: str, figures: dict[str, bytes]) -> str:
    """The PDF's HTML with its figure URLs replaced by data URIs (a self-contained file)."""
    for url, data in figures.items():
        html = html.replace(f'src="{url}"', 'src="data:image/jpeg;base64,'
                            + base64.b64encode(data).decode("ascii") + '"')
    return html


KEEP_ROWS = 14
"""Tables up to this many rows are never split across pages (nor from their heading)."""


def _groups(blocks: list[dict]) -> list[list[dict]]:
    """Blocks in page-layout groups: a heading travels with the block after it (a figure,
    text or a short table), or becomes the header row of a long table, so that no heading
    is left at the bottom of a page."""
    out: list[list[dict]] = []
    k = 0
    while k < len(blocks):
        b = blocks[k]
        nxt = blocks[k + 1] if k + 1 < len(blocks) else None
        if b["type"] == "heading" and nxt is not None and nxt["type"] == "table" and len(
                nxt["rows"]) > KEEP_ROWS:
            # before a long table the heading is the table's first header row: it repeats
            # on the continuation pages and can never be left alone at a page bottom
            out.append([dict(nxt, title=b["text"])])
            k += 2
        elif b["type"] == "heading" and nxt is not None:
            out.append([b, nxt])
            k += 2
        else:
            out.append([b])
            k += 1
    return out


def _nothing_judged(b: dict, header: str = "judged by") -> str:
    """Why no row of a judged-worst-case table is judged by a rule ('' if one is): such a
    table is computed information, which the results workbook carries."""
    cols = b.get("columns") or []
    if header not in cols or not b.get("rows"):
        return ""
    k = cols.index(header)
    vals = [str(row[k]) for row in b["rows"] if len(row) > k]
    if not vals or not all(v.startswith(("not judged", "no rule")) for v in vals):
        return ""
    reasons = dict.fromkeys(re.sub(r"^not judged:\s*", "", v) for v in vals)
    return "; ".join(reasons)


def _collapse_constant_column(b: dict, header: str = "judged by") -> dict:
    """A ``header`` column with the same text in every row (e.g. "not judged: no limit
    given for BRG-007" on 34 rows) leaves the table: the caption says it once."""
    cols = b.get("columns") or []
    if header not in cols or len(b.get("rows") or []) < 3:
        return b
    k = cols.index(header)
    css = b.get("row_css") or [""] * len(b["rows"])
    plain_rows = [row for row, c in zip(b["rows"], css) if "not-judged" not in (c or "")]
    vals = {row[k] for row in plain_rows if len(row) > k}
    if len(vals) != 1 or len(plain_rows) < 3:
        return b
    v = vals.pop()
    if len(plain_rows) != len(b["rows"]):  # marked rows keep their own text (said once)
        rows = [row[:k] + ["-"] + row[k + 1:] if "not-judged" not in (c or "") else row
                for row, c in zip(b["rows"], css)]
        return dict(b, rows=rows, caption=(b.get("caption") or "").rstrip(".")
                    + f". Unmarked rows: {v}.")
    out = dict(b, columns=cols[:k] + cols[k + 1:],
               rows=[row[:k] + row[k + 1:] for row in b["rows"]],
               caption=(b.get("caption") or "").rstrip(".") + f". Every row: {v}.")
    if b.get("widths") and len(b["widths"]) == len(cols):
        w = b["widths"][:k] + b["widths"][k + 1:]
        scale = sum(b["widths"]) / max(sum(w), 1e-9)
        out["widths"] = [round(x * scale, 1) for x in w]
    return out


def _collapse_marked_reason(b: dict, header: str = "judged by") -> dict:
    """The marked rows of a judged-worst-case table (points the rules do not judge) giving
    one to three reasons, each repeated ("not judged: outside the operating envelope", two or
    three lines in every such row), say "not judged" (numbered when there are several
    reasons); a note under the caption (``note``) gives each reason once. The same words,
    a shorter table."""
    cols = b.get("columns") or []
    css = b.get("row_css") or []
    if header not in cols or len(css) != len(b.get("rows") or []):
        return b
    k = cols.index(header)
    short = "not judged"
    marked = [i for i, c in enumerate(css) if "not-judged" in (c or "")
              and len(b["rows"][i]) > k and str(b["rows"][i][k]).startswith(short + ":")]
    reasons = list(dict.fromkeys(str(b["rows"][i][k]) for i in marked))
    if len(marked) < 2 or len(reasons) > 3 or len(reasons) == len(marked):
        return b
    rows = [list(row) for row in b["rows"]]
    for i in marked:
        n = reasons.index(str(rows[i][k]))
        rows[i][k] = short if len(reasons) == 1 else f"{short} ({n + 1})"
    said = reasons[0] if len(reasons) == 1 else "; ".join(
        f"({n + 1}) {r}" for n, r in enumerate(reasons))
    return dict(b, rows=rows, note=f"Marked rows: {said}.")


def _data_text(data, sheets: set[str]) -> str:
    """Where the numbers behind a plot are (the results workbook's sheets)."""
    names = []
    for d in data or []:
        name = results_book.sheet_name(d["sheet"] if isinstance(d, dict) else str(d))
        if name in sheets and name not in names:
            names.append(name)
    if not names:
        return ""
    return (f"Data: {results_book.ATTACHMENT_NAME}, sheet{'s' if len(names) > 1 else ''} "
            + ", ".join(names) + ".")


def _split_details(sections: list[dict]) -> tuple[list[dict], list[dict]]:
    """Tables marked ``detail`` leave the body for the results workbook; figure ``data``
    sheets that are not quantities are collected for it too."""
    extra: list[dict] = []
    for s in sections:
        keep = []
        n_table = 0
        for b in s["blocks"]:
            why = ""
            if b["type"] == "table":
                n_table += 1
                why = _nothing_judged(b)
                if why:
                    b = dict(b, detail=True, sheet=b.get("sheet") or f"{s['id']} {n_table}")
                else:
                    b = _collapse_marked_reason(_collapse_constant_column(b))
            if b["type"] == "table" and b.get("detail"):
                sheet = results_book.sheet_name(b.get("sheet") or f"{s['id']} table")
                extra.append({"sheet": sheet, "title": b.get("caption", ""),
                              "columns": b["columns"], "rows": b["rows"]})
                keep.append({"type": "text", "text": (b.get("caption") or "Table").rstrip(".")
                             + f": in {results_book.ATTACHMENT_NAME}, sheet {sheet}"
                             + (f" (no row is judged: {why})." if why else ".")})
                continue
            if b["type"] == "figure":
                extra += [d for d in b.get("data") or [] if isinstance(d, dict)]
            keep.append(b)
        s["blocks"] = keep
    return sections, extra


def _fail_on_text(fail_on: str) -> str:
    modes = fail_on.split(",")
    parts = ["a rule of severity error fails"]
    if "warning" in modes:
        parts.append("a warning-severity rule fails")
    if "not-evaluated" in modes:
        parts.append("a result cannot be evaluated")
    return ", ".join(parts[:-1]) + (" or " if len(parts) > 1 else "") + parts[-1]


def _verdict_words(res: CheckResult) -> str:
    c = res.counts()
    if res.verdict == "fail":
        n = len(res.failed)
        head = (f"{n} results fail their limits." if n != 1 else "1 result fails its limit.")
    else:
        head = "No result fails its limit."
    na = c["not_applicable"]
    tail = (f" {na} result{'s' if na != 1 else ''} not applicable: a rule or item the rule"
            " does not cover, listed with the reason after this page; not a pass." if na
            else "")
    if res.complete:
        return head + " Complete: every selected result was evaluated." + tail
    ne = c["not_evaluated"]
    return (head + f" Incomplete: {ne} result{'s' if ne != 1 else ''} could not be evaluated"
            " (missing inputs, listed after this page); they are not passes." + tail)


PLAIN = ((re.compile(r"\bTV (module|model)\b"), "torsional model"),
         (re.compile(r"\btv peak\b"), "TV peak"),
         (re.compile(r"\bsigma_DW\b"), "σ_DW"),
         (re.compile(r"\bthe loads module\b"), "the load analysis"),
         (re.compile(r"\bworkbook \(JointTorques\)"), "workbook (sheet JointTorques)"))
"""Internal names in texts written by the analyses, as a reader says them."""


def plain(text: str) -> str:
    """``text`` with the analyses' internal names in engineering words."""
    for pat, rep in PLAIN:
        text = pat.sub(rep, text)
    return text


def _plain_sections(sections: list[dict]) -> list[dict]:
    """Every text of the sections (intro, captions, cells, lists) in engineering words."""
    for sec in sections:
        sec["intro"] = plain(sec.get("intro") or "")
        for b in sec["blocks"]:
            for key in ("text", "caption", "title"):
                if isinstance(b.get(key), str):
                    b[key] = plain(b[key])
            if b["type"] == "list":
                b["items"] = [plain(str(x)) for x in b["items"]]
            elif b["type"] == "table":
                b["rows"] = [[plain(c) if isinstance(c, str) else c for c in row]
                             for row in b["rows"]]
            elif b["type"] == "equations":
                b["items"] = [tuple(plain(x) for x in it) for it in b["items"]]
    return sections


def _short_source(src: str) -> str:
    return src


def _assumption_groups(res: CheckResult) -> list[dict]:
    """Assumptions by sheet (workbook order; the model's own last), source text cut at
    about two lines (full text in the results workbook)."""
    out: dict[str, list[dict]] = {}
    for a in review.assumption_rows(res):
        sheet = a["sheet"] or "Model (checker's own assumptions)"
        src = plain(a["source"])
        # a parameter's reason in full (two lines); a table row's and the model's notes their
        # gist (full texts in the results workbook; the sections describe the model)
        cut = 230 if a["parameter"] != "table rows" and a["sheet"] else 140
        if len(src) > cut:
            src = src[:cut - 5].rsplit(" ", 1)[0] + " …"
        out.setdefault(sheet, []).append(dict(a, source=src))
    return [{"sheet": k if k.startswith("Model") else f"Sheet {k}", "rows": v}
            for k, v in out.items()]


def _extra_sheets(res: CheckResult) -> list[dict]:
    """Sheets of the results workbook for what the PDF shortens: the full rule table and
    the full assumption texts."""
    rules = [[r.id, r.name, r.severity, r.applies_to or "-", r.limit_text(), r.source,
              r.rationale] for r in res.table.rules]
    assum = [[a["sheet"] or "model", a["cell"], a["parameter"], a["value"], a["source"]]
             for a in review.assumption_rows(res)]
    return [{"sheet": "Rule table", "title": "Every rule: what it checks, where it applies,"
             " its limit, source and rationale", "columns": ["rule", "name", "severity",
                                                              "applies to", "limit", "source",
                                                              "rationale"], "rows": rules},
            {"sheet": "Assumptions", "title": "Inputs marked as assumptions and the model's"
             " own assumptions", "columns": ["sheet", "cell", "parameter", "value",
                                              "source or reason"], "rows": assum}]


def context(res: CheckResult, sections: list[dict] | None = None,
            results_file: str | None = None, figures: dict[str, bytes] | None = None,
            pending: dict[str, tuple[int, int]] | None = None,
            front: dict | None = None) -> dict:
    """Everything the template shows (formatting only). ``sections``: built sections
    (default: built here); ``figures``: collects the figures served by URL, ``pending`` the
    placeholders among them (see :func:`_figure_sources`; default: data URIs); ``front``:
    :func:`front_context` of the same arguments, if computed already."""
    if sections is None:
        sections = SectionJob(res).result()
    if front is None:
        front = front_context(res, results_file)
    return {**front,
            "sections": [dict(x, groups=_groups(x["blocks"]))
                         for x in _figure_sources(sections, figures, pending)]}


def front_context(res: CheckResult, results_file: str | None = None) -> dict:
    """What the template shows apart from the sections (see :func:`context`): computed while
    the drawing processes build the sections."""
    from .section_loads import lining_text

    groups = summary.groups(res)
    selected = {r.id for r in res.rules}
    rule_rows = [{"id": r.id, "name": r.name, "quantity": r.quantity,
                  "applies": r.applies_to or "-", "limit": r.limit_text()
                  + ("" if not r.limits else " (" + "; ".join(
                      f"{lining_text(k)} {'..'.join(f'{x:g}' for x in v)}"
                      for k, v in r.limits.items())
                      + ")"),
                  "severity": r.severity, "source": r.source, "rationale": r.rationale,
                  "source_short": _short_source(r.source),
                  "selected": r.id in selected} for r in res.table.rules]
    from .sections import LABELS, load_sections

    load_sections()
    timings = [{"module": LABELS.get(m, m.replace("_", " ")),
                "seconds": f"{res.outcome.timings.get(m, 0.0) * 1e3:.0f} ms"}
               for m in res.outcome.modules_run]
    fails = [r for g in groups if g["kind"] == "fail" for r in g["rows"]]
    near = summary.look_first(res)
    for r in [r for g in groups for r in g["rows"]] + near:
        r.note = plain(r.note)
    caveats = [dict(c, items=[plain(x) for x in c["items"]]) for c in review.caveats(res)]
    return {
        "title": f"Crank-train design-rule check: {res.engine.name}",
        "engine": res.engine.name,
        "date": _dt.date.today().isoformat(),
        "input_file": res.engine.source.replace("\\", "/").split("/")[-1],
        "sha256": res.engine.sha256,
        "version": __version__,
        "verdict": res.verdict_text,
        "verdict_css": res.verdict + ("" if res.complete else " incomplete"),
        "verdict_words": _verdict_words(res),
        "complete": res.complete,
        "fail_on": res.fail_on,
        "fail_on_text": _fail_on_text(res.fail_on),
        "counts": res.counts(),
        "groups": groups,
        "cover_groups": [g for g in groups if g["kind"] != "pass"],
        "look_first": near,
        "failed": fails,
        "failures": review.rank_failures(fails),
        "caveats": caveats,
        "doc_control": review.document_control(res),
        "rule_count": len(res.table.rules),
        "assumption_groups": _assumption_groups(res),
        "rule_rows": rule_rows,
        "rule_files": [f.replace("\\", "/").split("/")[-1] for f in res.table.files],
        "overrides": res.table.overrides,
        "assumptions": res.assumptions,
        "input_warnings": [str(w) for w in res.engine.warnings],
        "estimates": estimate_caveat(res.engine, res.results),
        "sizing_history": sizing_history(res.engine),
        "modules_run": res.outcome.modules_run,
        "modules_skipped": [LABELS.get(m, m.replace("_", " "))
                            for m in res.outcome.modules_skipped],
        "timings": timings,
        "attachment": results_book.ATTACHMENT_NAME,
        "results_file": results_file,
        "css": (templates_dir() / "report.css").read_text(encoding="utf-8"),
    }


def sizing_history(engine) -> list[str]:
    """The sizing loop's history of a layout written by ``checker new`` (the notes of the
    values it moved, :data:`checker.sizing.loop.HISTORY_MARK`): one line per move, by round;
    none for another workbook."""
    import re

    from ..sizing.loop import HISTORY_MARK

    lines: list[str] = []
    for e in getattr(engine, "estimates", ()) or ():
        for part in str(e).split(f"[{HISTORY_MARK} ")[1:]:
            text = part.split("]")[0].strip()
            if text and text not in lines:
                lines.append(text)

    def rnd(t: str) -> int:
        m = re.match(r"round (\d+)", t)
        return int(m.group(1)) if m else 0

    return sorted(lines, key=rnd)


def render_html(res: CheckResult) -> str:
    """The report as a standalone HTML string."""
    return _environment().get_template("report.html").render(**context(res))


def render_pdf(html: str, res: CheckResult, attachments: list[tuple[str, bytes, str]] = ()
               ) -> bytes:
    """The report as PDF bytes (same input -> same bytes on the same day); ``attachments``:
    ``(name, bytes, description)`` embedded files."""
    wp = load_weasyprint()
    doc = html_class(wp)(string=html, base_url=str(templates_dir())).render()
    return write_pdf(wp, doc, html, attachments)


@dataclass
class Report:
    """A rendered report: the PDF, the HTML (if asked), the results workbook, the page count
    and the time of each stage [s]."""

    pdf: bytes
    html: str
    results: bytes
    pages: int
    stages: dict[str, float] = field(default_factory=dict)
    cpu: dict[str, float] = field(default_factory=dict)
    """Processor time of each stage [s] (this process; "figures": the drawing processes),
    which a busy machine inflates far less than the wall time."""
    document: object = None
    """The laid-out WeasyPrint document (page boxes), for layout checks."""


DRAWING_NICE = 5
"""Scheduling priority increment of the drawing processes (``os.nice``): the PDF layout is the
longest piece of the report that cannot be split, and the figures are needed only when the
laid-out PDF is written, so the layout takes a core of its own and the drawing processes share
what is left (on two cores three processes would otherwise share them equally). Linux gives a
process at nice 5 a third of the weight of one at 0: enough for the layout to keep its core,
not so little that other work on a shared machine starves the drawing."""


def build_report(res: CheckResult, progress: Progress | None = None,
                 results_file: str | None = None, want_html: bool = True,
                 drawing: SectionJob | None = None, engine: PdfEngine | None = None
                 ) -> Report:
    """Figures, HTML, PDF layout and file, with the results workbook attached; the
    standalone HTML (figures as data URIs) when ``want_html``.

    ``drawing``: the module sections already being drawn (:func:`start_drawing`, started
    before the remedies' search); the sections it lacks (remedies and corners) are built
    here. ``engine``: the PDF engine process started before the analysis
    (:func:`checker.report.pdf_process.start`), which lays the PDF out and writes it (the
    report's ``document`` is then None); without it, this process does."""
    say = progress or (lambda _text: None)
    clock = _Clock()
    # the results workbook's quantity sheets written from now on, in a process of its own
    # (while pyplot is imported and the sections are built), the sections' tables given later
    book_job = ForkedCall(results_book.build_fed, res, fed=True, nice=DRAWING_NICE)
    try:
        # workers build the sections, then build and draw their figures while the PDF is
        # laid out (placeholders of the figures' size in the layout)
        job = drawing if drawing is not None else SectionJob(res, progress, defer=True,
                                                             nice=DRAWING_NICE)
    except BaseException:
        book_job.close()
        raise
    try:
        wp = load_weasyprint() if engine is None else None
        # while the drawing processes build the sections: the template compiled, the pages
        # before the sections and the sections the job was started without (the remedies and
        # corners, found after it)
        template = _environment().get_template("report.html")
        front = front_context(res, results_file)
        own = [SECTIONS[m](res) for m in modules_with_sections(res) if m not in job.mods]
        extra_sheets = _extra_sheets(res)
        clock.stage("template and front pages" if engine is not None
                    else "PDF engine import, template and front pages")
        children = children_cpu()
        sections = job.result() + own
        clock.stage("sections (figures set up)", extra_cpu=children_cpu() - children)
        sections, extra = _split_details(_plain_sections(sections))
        extra += extra_sheets
        say("Writing the results workbook")
        # finished while the PDF is laid out (the layout keeps its core: see DRAWING_NICE)
        book_job.feed(extra)
        from .results_book import sheet_names

        sheets = sheet_names(res, extra)
        for s in sections:
            for b in s["blocks"]:
                if b["type"] == "figure" and "data_text" not in b:
                    b["data_text"] = _data_text(b.get("data"), sheets)
        figures: dict[str, bytes] = {}
        pending: dict[str, tuple[int, int]] = {}
        html = template.render(**context(res, sections, results_file, figures, pending,
                                         front))
        clock.stage("HTML")
        if engine is not None:
            pdf, pages, book = _in_engine(engine, html, figures, pending, job, book_job, say,
                                          clock)
            return Report(pdf, standalone_html(html, figures) if want_html else "", book,
                          pages, clock.wall, clock.cpu, None)
        images = FigureCache()  # WeasyPrint's image cache (URL -> image, key -> image data)
        logger = logging.getLogger("weasyprint.progress")
        handler = PageProgress(say)
        old_level = logger.level
        logger.addHandler(handler)
        logger.setLevel(logging.INFO)
        try:
            doc = html_class(wp)(string=html, base_url=str(templates_dir()),
                                  url_fetcher=fetcher(wp, figures)).render(cache=images)
        finally:
            logger.removeHandler(handler)
            logger.setLevel(old_level)
        clock.stage("PDF layout")
        children = children_cpu()
        book = book_job.result()
        clock.stage("results workbook", extra_cpu=children_cpu() - children)
        say(f"Writing the PDF ({len(doc.pages)} pages)")
        pdf = write_with_figures(wp, doc, html, book, images, figures, pending, job.images)
    except BaseException:  # no drawing or workbook process outlives the report
        job.close()
        book_job.close()
        raise
    clock.stage("PDF write")
    clock.wall["of which waiting for the figures"] = images.wait
    clock.cpu["figures drawn during the layout"] = images.children_cpu
    return Report(pdf, standalone_html(html, figures) if want_html else "", book,
                  len(doc.pages), clock.wall, clock.cpu, doc)


def _in_engine(engine: PdfEngine, html: str, figures: dict[str, bytes],
               pending: dict[str, tuple[int, int]], job: SectionJob, book_job: ForkedCall,
               say: Progress, clock: _Clock) -> tuple[bytes, int, bytes]:
    """The PDF laid out and written by the engine process: the HTML sent, then the results
    workbook and the drawn figures (``figures`` gets them, for the standalone HTML) as they
    are ready; the engine's progress told meanwhile. ``(pdf, pages, results workbook)``;
    the engine's stage times in ``clock``."""
    engine.lay_out(html, figures, pending)
    children = children_cpu()
    book = book_job.result()
    clock.stage("results workbook", extra_cpu=children_cpu() - children)
    engine.send("book", book)
    got: list[tuple] = []

    def from_engine() -> None:
        r = engine.handle(say)
        if r is not None:
            got.append(r)

    children = children_cpu()
    drawn = job.images(also=(engine.conn, from_engine))
    clock.stage("figures drawn (beside the layout)", extra_cpu=children_cpu() - children)
    if pending and not got:
        engine.send("images", {key: bytes(drawn[key]) for key in pending.values()})
        for url, key in pending.items():
            figures[url] = bytes(drawn[key])
    pdf, pages, times = got[0] if got else engine.result(say)
    clock.stage("waiting for the PDF engine")
    for name, key in (("PDF layout", "layout"), ("PDF write", "write")):
        clock.wall[name], clock.cpu[name] = times[key]
    clock.wall["of which waiting for the figures"] = times["wait"][0]
    return pdf, pages, book


def start_drawing(res: CheckResult, progress: Progress | None = None) -> SectionJob:
    """The module sections of ``res`` drawn from now on in worker processes at the lowest
    priority: started before the remedies' and corners' search, they take the processor time
    that the search leaves idle (its rounds wait for their slowest variant) instead of
    running after it. Give the job to :func:`build_report`."""
    return SectionJob(res, progress, nice=19, defer=True)


class _Clock:
    """Wall and processor time per stage."""

    def __init__(self):
        self.wall: dict[str, float] = {}
        self.cpu: dict[str, float] = {}
        self._t, self._c = time.perf_counter(), time.process_time()

    def stage(self, name: str, extra_cpu: float = 0.0) -> None:
        t, c = time.perf_counter(), time.process_time()
        self.wall[name] = t - self._t
        self.cpu[name] = c - self._c + extra_cpu
        self._t, self._c = t, c
