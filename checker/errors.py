"""User-facing error types. Each carries what the user needs to fix the input; no traceback."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class InputError:
    """One problem in the input: where (``Sheet!B4``, a sheet, or a file) and what."""

    where: str
    message: str

    def __str__(self) -> str:
        return f"{self.where}: {self.message}"


class CheckerError(Exception):
    """Base class for errors that end a run with exit code 2."""

    exit_code = 2


class InputErrors(CheckerError):
    """All problems found in one workbook."""

    def __init__(self, errors: list[InputError], warnings: list[InputError] | tuple = (),
                 source: str = "", follow_on: int = 0):
        self.errors = list(errors)
        self.warnings = list(warnings)
        self.source = source  # the file's name when several workbooks are read (compare)
        # cross-checks held back because they need rows these errors left out
        self.follow_on = follow_on
        super().__init__("\n".join(str(e) for e in self.errors))

    def __str__(self) -> str:
        n = len(self.errors)
        where = f" {self.source}" if self.source else ""
        head = f"{n} problem{'s' if n != 1 else ''} in the input{where}:"
        text = head + "\n" + "\n".join(f"  {e}" for e in self.errors)
        if self.follow_on:
            k = self.follow_on
            text += (f"\n  ({k} cross-check{'s' if k != 1 else ''} of other rows held back:"
                     f" {'they need' if k != 1 else 'it needs'} the rows these cells left out;"
                     f" {'they run' if k != 1 else 'it runs'} again once the cells are"
                     " corrected)")
        if self.warnings:
            m = len(self.warnings)
            text += (f"\nand {m} warning{'s' if m != 1 else ''}:\n"
                     + "\n".join(f"  {w}" for w in self.warnings))
        return text


class RuleFileError(CheckerError):
    """A malformed rule table."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        super().__init__("\n".join(problems))

    def __str__(self) -> str:
        n = len(self.problems)
        head = f"{n} problem{'s' if n != 1 else ''} in the rule table:"
        return head + "\n" + "\n".join(f"  {p}" for p in self.problems)


class UsageProblem(CheckerError, ValueError):
    """A command-line or API usage problem (unknown selector, bad option value)."""


class InternalError(CheckerError):
    """A calculation failed on input it should never have received (a bug in checker):
    reported with a short message and exit code 2, never as a usage error."""


class OutputError(CheckerError):
    """An output cannot be written (read-only folder, a folder where a file is wanted):
    exit code 2, found before any long work starts (:mod:`checker.outputs.files`)."""
