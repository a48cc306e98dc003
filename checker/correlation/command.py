"""The ``checker correlate`` command's work (the option parsing is in :mod:`checker.cli`).

Every output (the PDF, the JSON file, the calibrated workbook) is probed before the work and
written all or none; a bad measurement file or workbook is exit code 2 with every problem at
its ``file:line`` or cell and no output; the input workbook is never modified.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import click

from ..errors import InputErrors, UsageProblem


def parse_orders(text: str | None) -> list[float] | None:
    """``"2,4,6"``, ``"0.5-12"`` (every half order between) or a mix; None for no text."""
    if not text:
        return None
    out: set[float] = set()
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        try:
            if "-" in part[1:]:
                a, b = (float(x) for x in part.split("-", 1))
                if b < a:
                    raise ValueError
                k = int(round(2 * a))
                while k / 2 <= b + 1e-9:
                    out.add(k / 2)
                    k += 1
            else:
                out.add(float(part))
        except ValueError:
            raise UsageProblem(f"--orders: expected orders like '2,4,6' or '0.5-12', found"
                               f" '{part}'") from None
    bad = [o for o in out if o <= 0 or abs(2 * o - round(2 * o)) > 1e-9]
    if bad:
        raise UsageProblem(f"--orders: {min(bad):g} is no positive multiple of 0.5")
    return sorted(out)


def run_command(workbook: str, measured: str, output: str | None, json_out: str | None,
                calibrated: str | None, fit: bool, fit_excitation: bool, orders: str | None,
                progress, cli: dict) -> None:
    """``cli``: the command line's ``fail``, ``outputs_writable`` and ``write_all`` (exit
    code 2 with one sentence; outputs probed before the work and written all or none) and
    the report's ``render`` (:func:`checker.report.section_correlation.render`), handed down
    so that this layer imports neither."""
    from . import run, to_dict

    _fail, _outputs_writable, _write_all = cli["fail"], cli["outputs_writable"], cli["write_all"]

    if calibrated and not fit:
        raise click.UsageError("--calibrated with --no-fit: nothing is fitted, so no calibrated"
                               " copy is written")
    wb = Path(workbook)
    pdf = Path(output) if output else wb.with_name(wb.stem + "-correlation.pdf")
    cal = (Path(calibrated) if calibrated else wb.with_name(wb.stem + "-calibrated.xlsx")
           ) if fit else None
    outs = [pdf] + ([Path(json_out)] if json_out and json_out != "-" else []) + (
        [cal] if cal else [])
    for p in outs:
        if p.resolve() == Path(measured).resolve():
            raise click.UsageError(f"output {p} would overwrite the measurement file")
    _outputs_writable(outs, workbook)
    try:
        asked = parse_orders(orders)
        c = run(workbook, measured, fit=fit, fit_excitation=fit_excitation, orders=asked,
                progress=progress)
    except UsageProblem as exc:
        raise click.UsageError(str(exc)) from None
    except InputErrors as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except Exception as exc:  # noqa: BLE001 - reported without traceback
        _fail(exc)
    try:
        files: list[tuple[Path, bytes]] = []
        cal_name = None
        if c.fit is not None and cal is not None:
            from .calibrated import calibrated_workbook

            m = c.measurement
            where = f"{m.station}, {m.load} load" + (
                "" if m.temperature is None else f", damper at {m.temperature - 273.15:.0f} °C")
            data, _cells = calibrated_workbook(workbook, c.fit, m.source, where)
            _loads_back(data)
            files.append((cal, data))
            cal_name = cal.name
        progress("Drawing the correlation report")
        _html, pdf_bytes = cli["render"](c, workbook, cal_name)
        files.insert(0, (pdf, pdf_bytes))
        text = json.dumps(to_dict(c, cal_name), indent=2, sort_keys=True,
                          ensure_ascii=False) + "\n"
        if json_out and json_out != "-":
            files.append((Path(json_out), text.encode("utf-8")))
    except Exception as exc:  # noqa: BLE001
        _fail(exc)
    _write_all(files)
    if json_out == "-":
        click.echo(text, nl=False)
    f = c.fit
    summary = (f"residual {f.rms_before * 100:.1f} % -> {f.rms_after * 100:.1f} %; "
               + ", ".join(f"{p.label} x{p.factor:.3g}" for p in f.parameters)
               if f is not None else "no fit")
    click.echo(f"wrote {', '.join(str(p) for p, _ in files)} ({summary})", err=True)


def _loads_back(data: bytes) -> None:
    """The calibrated copy must read back as a valid workbook (a bug otherwise)."""
    from ..description.engine import load_engine
    from ..errors import InternalError

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "calibrated.xlsx"
        p.write_bytes(data)
        try:
            load_engine(p)
        except InputErrors as exc:
            raise InternalError(f"the calibrated workbook does not read back: {exc}") from None
