"""Command line: ``checker template | new | check | report | study | compare | correlate |
rules``.

Exit codes: 0 no error-severity rule fails; 1 a rule fails; 2 bad input, bad rule file,
unwritable output or usage error; 130 interrupted (SIGINT, Ctrl-C); 143 terminated (SIGTERM).
Problems are printed without a traceback (set ``CHECKER_DEBUG=1`` to see one). Every output
is probed for writability before the work starts and written whole or not at all.
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
from pathlib import Path

# One BLAS thread unless the user asks for more (before NumPy is first imported): the check's
# matrix products are small, and OpenBLAS's idle worker threads spin after each call (about
# 0.2 s of processor time of an I4 check, 15 % of it, with no gain in wall time on 2 cores;
# docs/benchmarks.md, issue 37). Processes forked or started from here inherit it.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import click  # noqa: E402

from . import __version__
from .errors import CheckerError, InternalError, OutputError, UsageProblem
from .outputs.files import check_writable, write_files
from .plumbing.interrupt import EXIT_SIGINT, EXIT_SIGTERM, Terminated, checkpoint, sigterm_raises


def _split(values: tuple[str, ...]) -> list[str] | None:
    out = [v.strip() for s in values for v in s.split(",") if v.strip()]
    return out or None


# what each calculation of the graph computes, in words (progress lines)
STEP_WORDS = {
    "balance": "the balance of the rotating and reciprocating masses",
    "crank_geometry": "the crank's throws from its geometry",
    "fillet_bending_ratio": "the fillet bending of the continuous beam against the"
                            " determinate scheme",
    "pressure_traces": "the cylinder pressure traces",
    "bearing_loads": "the bearing loads",
    "specific_load": "the specific bearing loads",
    "bearing_heat_balance": "the oil-film temperatures (bearing heat balance)",
    "film_pressure": "the peak oil-film pressures",
    "film_pressure_short": "the peak oil-film pressures (short-bearing theory)",
    "moft": "the minimum oil film thickness",
    "moft_short": "the minimum oil film thickness (short-bearing theory)",
    "moft_finite": "the minimum oil film thickness (finite-length bearing)",
    "tv_response": "the torsional vibration of the crank train",
    "tv_joint_torque": "the joint torques from the torsional model",
    "tv_crank_stress": "the crankshaft's vibratory shear stress",
    "tv_class_rules": "the crankshaft's vibratory stress against the class rules",
    "coupling_load": "the flexible coupling's torque and heat",
    "misfire_response": "the misfire case (each cylinder not firing in turn)",
    "misfire_crank_stress": "the crank's stress under misfire against the class limit",
    "damper_tuning": "the damper tuning",
    "damper_rubber_ends": "the damper rubber at the ends of its temperature range",
    "viscous_damper": "the viscous damper's heat and damping",
    "crank_fatigue": "the crankshaft fatigue safety factors",
    "crank_nose_fatigue": "the crank-nose fatigue safety factor",
    "flywheel": "the cyclic irregularity and flywheel inertia",
    "joint_bolts": "the bolt preloads and stresses of the joints",
    "joint_applied_torque": "the torques the joints must transmit",
    "joint_cover_factor": "the joints' slip safety (cover factors)",
    "joint_computed_torque": "the joint torques from the engine loads",
}


class _Progress:
    """Progress in words on stderr (by default only when stderr is a terminal). Page
    counters ("Laying out the PDF, page 12") overwrite each other on a terminal."""

    COUNTER = "Laying out the PDF, page "

    STEP = re.compile(r"^([a-z_]+): ([a-z_]+)$")

    def __init__(self, enabled: bool):
        self.enabled = enabled
        self.tty = sys.stderr.isatty()
        self.open_line = False
        self.page = 0

    def __call__(self, text: str) -> None:
        checkpoint()  # an interruption a callback swallowed ends the command here
        if not self.enabled:
            return
        m = self.STEP.match(text)
        if m:  # a calculation of the graph ("loads: pressure_traces")
            text = "Computing " + STEP_WORDS.get(m.group(2), "the " + m.group(2).replace(
                "_", " "))
        if text.startswith(self.COUNTER):
            n = int(text[len(self.COUNTER):].split()[0])
            if n <= self.page:  # a page laid out again (page references): no news
                return
            self.page = n
            if self.tty:
                click.echo(f"\rchecker: {text}", err=True, nl=False)
                self.open_line = True
                return
            if n % 10:
                return
        if self.open_line:
            click.echo("", err=True)
            self.open_line = False
        click.echo(f"checker: {text}", err=True)

    def done(self) -> None:
        if self.open_line:
            click.echo("", err=True)
            self.open_line = False


def _short(exc: BaseException, limit: int = 300) -> str:
    """First line of an exception text, cut to ``limit`` characters (no array dumps)."""
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _fail(exc: BaseException) -> None:
    if os.environ.get("CHECKER_DEBUG"):
        raise exc
    if isinstance(exc, CheckerError) and not isinstance(exc, InternalError):
        click.echo(f"error: {exc}", err=True)
    else:
        click.echo(f"internal error: {type(exc).__name__}: {_short(exc)}\n(this is a bug in"
                   " checker, not in your input; set CHECKER_DEBUG=1 for a traceback and"
                   " please report it with the workbook)", err=True)
    sys.exit(2)


def _run_check(workbook, rules, select, ignore, fail_on, progress, cache=None):
    from . import api

    try:
        res = api.check(workbook, rules=rules, select=_split(select), ignore=_split(ignore),
                        fail_on=",".join(fail_on) if fail_on else None, progress=progress,
                        cache=cache, parallel=True)
    except UsageProblem as exc:
        raise click.UsageError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001 - reported without traceback
        _fail(exc)
    if res.nothing_checked:
        # like a test runner that collected no tests: never a vacuous PASS, no output file
        click.echo(f"error: {res.nothing_checked_reason()}", err=True)
        sys.exit(2)
    return res


_extras = [
    click.option("--remedies", is_flag=True, help="What it takes to pass: per failing result"
                 " (and passing ones within 10 % of the limit) and design lever, the input"
                 " value at which the margin reaches zero, with side effects."),
    click.option("--corners", is_flag=True, help="Judge each result at the worst corner of the"
                 " workbook's Tolerances; the verdict uses the worst corner."),
    click.option("--levers", "levers_file", type=click.Path(exists=True, dir_okay=False),
                 help="Lever file ([[lever]] tables) adding to or restricting rules/levers.toml."),
]


def extras(f):
    for opt in reversed(_extras):
        f = opt(f)
    return f


def _attach_extras(res, workbook, rules, select, ignore, remedies, corners, levers_file, cache,
                   progress=None):
    """Remedies and tolerance corners on a finished check (checker.remedies)."""
    if not (remedies or corners):
        return
    from .remedies import attach

    if progress is not None:
        progress("Finding what it takes to pass and the tolerance corners")
    try:
        attach(res, remedies, corners, levers_file, cache, _split(select), _split(ignore), rules)
    except UsageProblem as exc:
        raise click.UsageError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001 - reported without traceback
        _fail(exc)


def _exit_code(res) -> int:
    if not res.corners:  # no tolerance corners asked: checker.remedies not imported
        return res.exit_code
    from .remedies import corners_fail

    return max(res.exit_code, 1 if corners_fail(res) else 0)


def _atomic_write(path: Path, data: bytes) -> None:
    """Write one output whole (via a temporary file in the same folder); a problem writing it
    is exit code 2 with one sentence (see :mod:`checker.outputs.files`)."""
    _write_all([(path, data)])


def _write_all(files: list[tuple[Path, bytes]]) -> None:
    """Write several outputs all or none; an OSError is exit code 2 with one sentence."""
    try:
        write_files(files)
    except OutputError as exc:
        _fail(exc)


def _outputs_writable(paths, workbook: str | None = None) -> None:
    """Before any work: each output is a distinct file, not the input workbook, and its folder
    is writable; otherwise exit code 2 with one sentence."""
    paths = [Path(p) for p in paths]
    if workbook is not None:
        for p in paths:
            if p.resolve() == Path(workbook).resolve():
                raise click.UsageError(f"output {p} would overwrite the input workbook")
    if len({p.resolve() for p in paths}) < len(paths):
        raise click.UsageError("the output files must be different files")
    try:
        check_writable(paths)
    except OutputError as exc:
        _fail(exc)


_common = [
    click.option("--rules", "rules", type=click.Path(exists=True),
                 help="Rule file or folder (default: the built-in rule table)."),
    click.option("--select", multiple=True, help="Run only rules with these id prefixes"
                 " (comma-separated or repeated), e.g. JNT or BRG-001."),
    click.option("--ignore", multiple=True, help="Skip rules with these id prefixes."),
    click.option("--fail-on", multiple=True, metavar="error|warning|not-evaluated",
                 help="What fails the check (default: error). 'warning': failed warnings"
                 " too; 'not-evaluated': results that could not be evaluated too; combine"
                 " with commas or repeat."),
]


def common(f):
    for opt in reversed(_common):
        f = opt(f)
    return f


WORKBOOK = click.argument("workbook", type=click.Path(exists=True, dir_okay=False))


class _Group(click.Group):
    """The command group: an interruption is exit code 130 (SIGINT, Ctrl-C) or 143 (SIGTERM)
    with one line, never click's "Aborted!" with exit code 1 (the verdict code). Outputs are
    written whole or not at all, so an interruption leaves no partial file."""

    def invoke(self, ctx: click.Context):
        try:
            with sigterm_raises():
                return super().invoke(ctx)
        except KeyboardInterrupt:
            click.echo("\ninterrupted", err=True)
            sys.exit(EXIT_SIGINT)
        except Terminated:
            click.echo("terminated", err=True)
            sys.exit(EXIT_SIGTERM)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="checker")
def main() -> None:
    """Design-rule checker for engine crank trains."""
    _keep_freed_memory()


def _keep_freed_memory() -> None:
    """Keep freed memory in the process (glibc ``mallopt``): the orbit kernels allocate and
    free arrays of a few MB thousands of times; by default each is a fresh ``mmap`` (or heap
    memory is returned to the system), and touching fresh pages again costs about 40 % more
    page faults, about 0.1 s of system time per check (benchmarks/bench_speed.py). Numbers
    are unchanged; elsewhere (other C libraries) nothing happens."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        libc = ctypes.CDLL(None)
        libc.mallopt(-3, 32 * 2**20)  # M_MMAP_THRESHOLD: arrays up to 32 MB on the heap
        libc.mallopt(-1, 128 * 2**20)  # M_TRIM_THRESHOLD: keep up to 128 MB of freed heap
    except (OSError, AttributeError):  # not glibc: the allocator's defaults
        return


@main.command()
@click.argument("path", type=click.Path(dir_okay=False), required=False)
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
@click.option("--engine", "which", type=click.Choice(["i4", "i6", "v8", "genset", "marine"],
                                                    case_sensitive=False),
              default="i4",
              show_default=True, help="i4: the gasoline engine of Bell, Ricardo 2013; i6: a"
              " truck diesel from Mendes et al. 2008 with an assumed viscous damper; v8: a"
              " 90-degree cross-plane V8 from GM LS1 service data; genset: an in-line six"
              " medium-speed diesel driving a generator through a flexible coupling; marine:"
              " the same engine driving a fixed-pitch propeller; assumptions labelled in each.")
def template(path: str, force: bool, which: str) -> None:
    """Write an example workbook to PATH (default: engine.xlsx for the I4, engine-i6.xlsx for
    the I6, engine-v8.xlsx for the V8)."""
    from .workbook.example import example_content, write_workbook
    from .workbook.example_classes import genset_content, marine_content
    from .workbook.example_i6 import i6_content
    from .workbook.example_v8 import v8_content

    which = which.lower()
    p = Path(path or ("engine.xlsx" if which == "i4" else f"engine-{which}.xlsx"))
    if p.suffix.lower() != ".xlsx":
        raise click.UsageError(f"{p} is not an .xlsx file name; the workbook is an Excel file"
                               f" (e.g. {p.with_suffix('.xlsx').name})")
    if p.exists() and not force:
        raise click.UsageError(f"{p} exists; use --force to overwrite it")
    _outputs_writable([p])
    content = {"i4": example_content, "i6": lambda: i6_content(damper_ring=True),
               "v8": v8_content, "genset": genset_content, "marine": marine_content}[which]()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d) / "engine.xlsx"
        write_workbook(tmp, content)
        _atomic_write(p, tmp.read_bytes())
    click.echo(f"wrote {p}", err=True)


@main.command("new")
@click.argument("path", type=click.Path(dir_okay=False))
@click.option("--brief", "brief_file", type=click.Path(exists=True, dir_okay=False),
              help="Brief file (TOML): cylinders, layout, bore, stroke, rated_power... (see"
              " docs/new-engine.md); options given as well win.")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
@click.option("--cylinders", type=int, default=None)
@click.option("--layout", default=None, help='"inline" or "V".')
@click.option("--bank-angle", "bank_angle", default=None, help='e.g. "90 deg" (V only).')
@click.option("--bore", default=None, help='e.g. "86 mm".')
@click.option("--stroke", default=None, help='e.g. "94.6 mm".')
@click.option("--rated-power", "rated_power", default=None, help='e.g. "110 kW".')
@click.option("--rated-speed", "rated_speed", default=None, help='e.g. "6000 rpm".')
@click.option("--max-speed", "max_speed", default=None, help='e.g. "7000 rpm".')
@click.option("--min-speed", "min_speed", default=None, help='e.g. "1000 rpm".')
@click.option("--peak-pressure", "peak_pressure", default=None, help='e.g. "85 bar".')
@click.option("--fuel", default=None, help='"gasoline" or "diesel".')
@click.option("--crank-material", "crank_material", default=None,
              help='"forged steel" or "nodular iron".')
@click.option("--bearing-lining", "bearing_lining", default=None,
              help='e.g. "aluminium bimetal", "tri-metal".')
@click.option("--engine-class", "engine_class", default=None,
              help='"passenger car", "commercial vehicle", "industrial" or "marine".')
@click.option("--crank-type", "crank_type", default=None,
              help='"shared pins", "split pins", "flat-plane", "cross-plane"; twins "180 deg",'
                   ' "270 deg", "360 deg".')
@click.option("--firing-order", "firing_order", default=None, help='e.g. "1-3-4-2".')
@click.option("--name", default=None, help="Engine name.")
@click.option("--no-iterate", "no_iterate", is_flag=True,
              help="Write the open-loop layout (every dimension by its rule) without checking"
              " it and moving its sizing levers until every rule passes.")
def new(path, brief_file, force, no_iterate, **options) -> None:
    """Write a first crank-train layout to PATH (.xlsx) from a concept brief: every derived
    value sized by a stated design rule with its source, marked ESTIMATE; then checked and
    its sizing levers moved until every rule passes (or the brief value that prevents it
    named), the history in its Notes."""
    from .errors import InputErrors
    from .sizing.brief import load_brief
    from .sizing.loop import sized
    from .sizing.new_engine import NoRule, warnings
    from .workbook.example import write_workbook

    p = Path(path)
    if p.suffix.lower() != ".xlsx":
        raise click.UsageError(f"{p} is not an .xlsx file name; the workbook is an Excel file"
                               f" (e.g. {p.with_suffix('.xlsx').name})")
    if p.exists() and not force:
        raise click.UsageError(f"{p} exists; use --force to overwrite it")
    if brief_file is None and not any(v is not None for v in options.values()):
        raise click.UsageError("give a brief: --brief brief.toml or the options --cylinders,"
                               " --bore, --stroke, --rated-power, --rated-speed ...")
    _outputs_writable([p])
    try:
        b = load_brief(brief_file, options)
        result = sized(b, iterate=not no_iterate)
        content = result.content
    except InputErrors as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except NoRule as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except Exception as exc:  # noqa: BLE001 - reported without traceback
        _fail(exc)
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d) / "engine.xlsx"
        write_workbook(tmp, content)
        _refused_by_the_check(tmp)  # never write geometry the check would refuse
        _atomic_write(p, tmp.read_bytes())
    for w in warnings(result.layout):
        click.echo(f"warning: {w}", err=True)
    if result.loop is not None:
        for line in result.loop.summary():
            click.echo(line, err=True)
    click.echo(f"wrote {p} (first layout; every value marked ESTIMATE names its rule and"
               " source)", err=True)


def _refused_by_the_check(path: Path) -> None:
    """Read the sized workbook as ``checker check`` will (every sheet, the crank's geometry,
    the rule overrides): an input error there is a rule of ``checker new`` without data for
    this brief, exit 2, nothing written."""
    from .description.engine import load_engine
    from .errors import InputErrors
    from .evaluation.ruletable import load_rules, override_problems

    table = load_rules()
    try:
        load_engine(path, check_overrides=lambda o: override_problems(table, o)[2])
    except InputErrors as exc:
        click.echo("error: the sized layout would be refused by the check (a rule of checker"
                   f" new has no data for this brief): {exc}", err=True)
        sys.exit(2)


@main.command()
@WORKBOOK
@common
@click.option("--format", "fmt", type=click.Choice(["text", "json", "junit"]), default="text",
              show_default=True)
@click.option("--no-timings", is_flag=True, help="Leave run times out of the JSON output.")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the output to a file instead of stdout.")
@click.option("--progress/--no-progress", default=None, help="Stage lines on stderr.")
@extras
def check(workbook, rules, select, ignore, fail_on, fmt, no_timings, output, progress,
          remedies, corners, levers_file) -> None:
    """Run the check as a CI gate: results on stdout, exit code 0/1/2, no PDF."""
    from .outputs import formats

    if output:
        _outputs_writable([output], workbook)
    prog = _Progress(sys.stderr.isatty() if progress is None else progress)
    cache: dict | None = {} if (remedies or corners) else None
    res = _run_check(workbook, rules, select, ignore, fail_on, prog, cache)
    _attach_extras(res, workbook, rules, select, ignore, remedies, corners, levers_file, cache)
    if fmt == "json":
        text = formats.to_json(res, timings=not no_timings)
    elif fmt == "junit":
        text = formats.to_junit(res)
    else:
        text = formats.to_text(res)
        if remedies or corners:
            from .remedies import to_text as _extra_text

            text += _extra_text(res)
    if output:
        _atomic_write(Path(output), text.encode("utf-8"))
        click.echo(f"{output}: {res.summary_text()}", err=True)
    else:
        click.echo(text, nl=False)
    sys.exit(_exit_code(res))


@main.command()
@WORKBOOK
@common
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="PDF file (default: the workbook name with .pdf).")
@click.option("--html", "html_out", type=click.Path(dir_okay=False),
              help="Also write the report as HTML.")
@click.option("--results", "results_out", type=click.Path(dir_okay=False),
              help="Also write the results workbook (every quantity, item, case and speed;"
              " it is attached to the PDF in any case), e.g. results.xlsx.")
@click.option("-q", "--quiet", is_flag=True, help="No progress lines (only the final line"
              " and errors).")
@click.option("--progress/--no-progress", default=None,
              help="Progress in words on stderr (default: when stderr is a terminal).")
@extras
def report(workbook, rules, select, ignore, fail_on, output, html_out, results_out, quiet,
           progress, remedies, corners, levers_file) -> None:
    """Render the pass/fail PDF report for the design-review pack."""
    prog = _Progress(False if quiet else sys.stderr.isatty() if progress is None
                     else progress)
    pdf_path = Path(output) if output else Path(workbook).with_suffix(".pdf")
    outs = [pdf_path] + [Path(x) for x in (html_out, results_out) if x]
    _outputs_writable(outs, workbook)
    from .report.pdf_process import start as start_pdf_engine

    # WeasyPrint imported and set up in a process of its own while the analysis runs here
    engine = start_pdf_engine()
    try:
        prog("Reading the workbook and running the analyses")
        cache: dict | None = {} if (remedies or corners) else None
        res = _run_check(workbook, rules, select, ignore, fail_on, prog, cache)
        if (res.engine.params.get("support_scheme") or "determinate") != "determinate":
            from .api import compare_schemes

            prog("Checking the determinate scheme beside the continuous beam")
            res.scheme_changes = compare_schemes(res)
        drawing = None
        if remedies or corners:
            from .report.render import start_drawing

            # the figures drawn with the processor time the search leaves idle
            drawing = start_drawing(res, prog)
        try:
            _attach_extras(res, workbook, rules, select, ignore, remedies, corners, levers_file,
                           cache, prog)
        except BaseException:
            if drawing is not None:  # a bad Tolerances sheet or lever file: no report to draw
                drawing.close()
            raise
        try:
            from .report.render import build_report

            rep = build_report(res, progress=prog, want_html=bool(html_out),
                               results_file=Path(results_out).name if results_out else None,
                               drawing=drawing, engine=engine)
        except Exception as exc:  # noqa: BLE001
            prog.done()
            _fail(exc)
        prog.done()
        files = [(pdf_path, rep.pdf)]
        if html_out:
            files.append((Path(html_out), rep.html.encode("utf-8")))
        if results_out:
            files.append((Path(results_out), rep.results))
        _write_all(files)  # all or none
        written = [str(p) for p, _ in files]
        click.echo(f"wrote {', '.join(written)} ({rep.pages} pages): {res.summary_text()}",
                   err=True)
        sys.exit(_exit_code(res))
    finally:
        if engine is not None:
            engine.close()


@main.command()
@WORKBOOK
@click.argument("study_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", "out_dir", type=click.Path(file_okay=False), required=True,
              help="Folder for the results (variants/, results.parquet, results.xlsx,"
              " study.pdf); re-running resumes.")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Local worker processes, at least 1 (default: one per core).")
@click.option("--dask", "dask_address", metavar="ADDRESS|local", default=None,
              help="Run on a Dask distributed cluster (scheduler address tcp://host:port), or"
              " 'local' for a LocalCluster.")
@click.option("--no-pdf", is_flag=True, help="Write the results tables only.")
@click.option("--progress/--no-progress", default=None,
              help="Progress bar on stderr (default: when stderr is a terminal).")
def study(workbook, study_file, out_dir, workers, dask_address, no_pdf, progress) -> None:
    """Run a parametric study (variants of WORKBOOK described by STUDY_FILE).

    Exit codes: 0 done (failing variants are results, not errors); 2 bad study file, base
    workbook, option or output folder; 130 interrupted (Ctrl-C), 143 terminated (SIGTERM),
    the finished variants kept for a re-run to resume."""
    from .plumbing.interrupt import interruptible
    from .study.results import write_tables
    from .study.run import check_output, connect_dask, output_lock, plan_study, run_plan
    from .study.spec import load_study

    show = sys.stderr.isatty() if progress is None else progress

    def say(text: str) -> None:
        click.echo(f"checker: {text}", err=True)

    state: dict = {}

    def kept() -> str:
        plan = state.get("plan")
        n = 0
        if plan is not None:
            folder = Path(out_dir) / "variants"
            n = sum(1 for k in plan.keys if (folder / f"{k}.json").is_file())
        return f"{n} variant{'s' if n != 1 else ''} kept in {out_dir}; re-run to resume"

    with interruptible(kept, echo=lambda line: click.echo(f"checker: {line}", err=True)):
        engine = None
        try:
            st = load_study(study_file)
            say(f"reading {workbook} and checking the study {Path(study_file).name}")
            plan = state["plan"] = plan_study(st, workbook)
            check_output(out_dir)
            if dask_address:
                say(f"connecting to Dask ({dask_address})")
                engine = connect_dask(dask_address, workers)
            with output_lock(out_dir):
                run = run_plan(plan, out_dir, workers=workers, dask=dask_address,
                               progress=show, say=say, client=engine)
                pdfs: list[str] = []

                def draw() -> None:  # while another process writes results.xlsx
                    from .report.study import render
                    from .study.results import report_frame

                    say("drawing the study report")
                    html, pdf = render(run, report_frame(out_dir, run))
                    _atomic_write(Path(out_dir) / "study.pdf", pdf)
                    pdfs.append(str(Path(out_dir) / "study.pdf"))

                say("writing results.parquet and results.xlsx")
                written = write_tables(run, out_dir, say=say,
                                       alongside=None if no_pdf else draw) + pdfs
        except UsageProblem as exc:
            raise click.UsageError(str(exc)) from None
        except Exception as exc:  # noqa: BLE001 - reported without traceback
            _fail(exc)
        finally:
            if engine is not None:
                engine.close()
    bad = run.input_errors()
    n = len(run.records)
    say(f"{n} variant{'s' if n != 1 else ''} ({run.computed} computed,"
        f" {len(run.records) - run.computed} resumed"
        f"{f', {len(bad)} with input errors' if bad else ''}) in {run.seconds:.1f} s;"
        f" wrote {', '.join(written)}")
    if bad:
        say(f"{len(bad)} variant{'s' if len(bad) != 1 else ''} not checked (input errors):")
        for b in bad:
            for e in b["errors"]:
                click.echo(f"  variant {b['variant']} ({b['name']}): {e}", err=True)


@main.command()
@click.argument("baseline", type=click.Path(exists=True, dir_okay=False))
@click.argument("variants", nargs=-1, required=True,
                type=click.Path(exists=True, dir_okay=False))
@common
@click.option("--format", "fmt", type=click.Choice(["pdf", "json"]), default="pdf",
              show_default=True)
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Output file (default: the baseline name with -compare.pdf; JSON: stdout).")
def compare(baseline, variants, rules, select, ignore, fail_on, fmt, output) -> None:
    """Compare BASELINE with VARIANTS: input changes, status changes first, curves overlaid.

    Exit code 1 when a variant has a failing result the baseline does not have."""
    import json as _json

    from .outputs import compare as cmp

    if output or fmt == "pdf":
        out = Path(output) if output else Path(baseline).with_name(
            Path(baseline).stem + "-compare.pdf")
        _outputs_writable([out])
        for w in (baseline, *variants):
            if out.resolve() == Path(w).resolve():
                raise click.UsageError(f"output {out} would overwrite the input workbook {w}")
    try:
        comps = cmp.compare(baseline, list(variants), select=_split(select),
                            ignore=_split(ignore),
                            fail_on=",".join(fail_on) if fail_on else "error")
    except UsageProblem as exc:
        raise click.UsageError(str(exc)) from None
    except Exception as exc:  # noqa: BLE001
        _fail(exc)
    worse = any(r["change"] == "newly failing" for c in comps for r in c.results)
    if fmt == "json":
        text = _json.dumps({"baseline": Path(baseline).name,
                            "comparisons": [c.to_dict() for c in comps]}, indent=2,
                           sort_keys=True, ensure_ascii=False) + "\n"
        if output:
            _atomic_write(out, text.encode("utf-8"))
        else:
            click.echo(text, nl=False)
    else:
        try:
            from .report.compare import render

            html, pdf = render(comps)
        except Exception as exc:  # noqa: BLE001
            _fail(exc)
        _atomic_write(out, pdf)
        click.echo(f"wrote {out}", err=True)
    for c in comps:
        n = sum(1 for r in c.results if r["change"] == "newly failing")
        click.echo(f"{Path(c.variant.engine.source).name}: {c.variant.verdict_text}"
                   f" ({c.inputs_text()}; {n} newly failing)", err=True)
    sys.exit(1 if worse else 0)


@main.command()
@WORKBOOK
@click.argument("measured", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="PDF file (default: the workbook name with -correlation.pdf).")
@click.option("--json", "json_out", type=click.Path(dir_okay=False, allow_dash=True),
              help="Also write the comparison and calibration as JSON ('-': stdout).")
@click.option("--calibrated", type=click.Path(dir_okay=False),
              help="Calibrated copy of the workbook (default: the workbook name with"
              " -calibrated.xlsx).")
@click.option("--no-fit", is_flag=True, help="Compare only: no calibration, no copy.")
@click.option("--fit-excitation", is_flag=True,
              help="Also fit one scale on the crank-torque harmonics.")
@click.option("--orders", help="Orders to compare, e.g. '2,4,6' or '0.5-12'.")
@click.option("--progress/--no-progress", default=None, help="Stage lines on stderr.")
def correlate(workbook, measured, output, json_out, calibrated, no_fit, fit_excitation, orders,
              progress) -> None:
    """Compare a measurement (order tracks or an angle-domain signal, MEASURED) with the
    torsional model of WORKBOOK and calibrate the model (docs/correlation.md)."""
    from .correlation.command import run_command
    from .report.section_correlation import render

    run_command(workbook, measured, output, json_out, calibrated, not no_fit, fit_excitation,
                orders, _Progress(sys.stderr.isatty() if progress is None else progress),
                {"fail": _fail, "outputs_writable": _outputs_writable, "write_all": _write_all,
                 "render": render})


@main.command("rules")
@click.option("--rules", "rules", type=click.Path(exists=True), help="Rule file or folder.")
@click.option("--explain", metavar="ID", help="Show one rule in full.")
def rules_cmd(rules, explain) -> None:
    """List the rule table, or explain one rule."""
    from .evaluation.ruletable import load_rules

    try:
        table = load_rules(rules)
    except CheckerError as exc:
        _fail(exc)
    if explain:
        want = explain.strip().upper()  # rule ids are case-insensitive, as in --select
        r = next((x for x in table.rules if x.id.upper() == want), None)
        if r is None:
            raise click.UsageError(f"no rule '{explain}' (see 'checker rules')")
        where = ", ".join(f"{k} = {'/'.join(v)}" for k, v in r.where.items()) or "-"
        lines = [f"{r.id}  {r.name}", f"  quantity:   {r.quantity}",
                 f"  applies to: {r.applies_to or where}", f"  where:      {where}",
                 f"  check:      {r.limit_text()}", f"  severity:   {r.severity}",
                 f"  source:     {r.source}", f"  rationale:  {r.rationale}",
                 f"  file:       {r.origin}"]
        if r.limits:
            u = f" {r.unit}" if r.unit else ""
            lines.insert(5, "  limits:     " + "; ".join(
                f"{k}: {'..'.join(f'{x:g}' for x in v)}{u}" for k, v in r.limits.items()))
        click.echo("\n".join(lines))
        return
    w = max(len(r.name) for r in table.rules)
    wi = max(len(r.id) for r in table.rules)
    for r in table.rules:
        click.echo(f"{r.id.ljust(wi)}  {r.name.ljust(w)}  {r.severity:<7}  {r.limit_text()}")


if __name__ == "__main__":  # pragma: no cover
    main()


def run() -> None:
    """The ``checker`` command (console script and ``python -m checker``): :func:`main`, then
    the objects alive at its end frozen out of the garbage collector's passes at interpreter
    exit, which scanned the whole heap (0.15-0.2 s after a report); they are still freed. Not
    in :func:`main` itself, which tests call in one long-lived process."""
    import gc

    from .plumbing import frame_stack

    try:
        frame_stack.call(main)
    finally:
        gc.freeze()
