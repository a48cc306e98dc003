"""Writing output files safely: every output's folder is probed before any long work starts,
and files appear whole or not at all.

- :func:`check_writable` (files) and :func:`check_writable_folder` (an output folder) raise
  :class:`~checker.errors.OutputError` (exit code 2, one plain sentence) when an output cannot
  be written: its folder is read-only or missing under a regular file, the path is a folder,
  the file is read-only. They probe by creating and deleting a temporary file, so what the
  operating system refuses (read-only mounts, access lists) is found, not guessed.
- :func:`write_files` writes several outputs all-or-nothing: every file goes to a temporary
  file beside its target first and only then are they renamed into place, so an interruption
  or a failing second file never leaves the first one written.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from ..errors import OutputError

_PREFIX = ".checker-"


def _reason(exc: OSError) -> str:
    return (exc.strerror or type(exc).__name__).lower()


def _existing_ancestor(folder: Path) -> Path:
    p = folder
    while not p.exists() and p != p.parent:
        p = p.parent
    return p


def _probe_folder(folder: Path, what: Path) -> None:
    """Raise OutputError unless a file can be created in ``folder`` (or, when it does not
    exist yet, in the folder that would hold it)."""
    anc = _existing_ancestor(folder)
    if not anc.is_dir():
        raise OutputError(f"cannot write {what}: {anc} is a file, not a folder")
    try:
        fd, tmp = tempfile.mkstemp(prefix=_PREFIX, dir=anc)
    except OSError as exc:
        where = "its folder" if anc == folder else "the folder"
        raise OutputError(f"cannot write {what}: {where} {anc} is not writable"
                          f" ({_reason(exc)})") from None
    os.close(fd)
    os.unlink(tmp)


def check_writable(paths: Iterable[str | Path]) -> None:
    """Raise :class:`OutputError` unless every file in ``paths`` can be written (created or
    replaced). Nothing is left behind by the probe."""
    for p in (Path(x) for x in paths):
        if p.is_dir():
            raise OutputError(f"output {p} is a folder; give a file name")
        if p.exists():
            if not p.is_file():  # a device (/dev/null), a FIFO: written to, never replaced
                if not os.access(p, os.W_OK):
                    raise OutputError(f"cannot write {p}: permission denied")
                continue
            if not os.access(p, os.W_OK):
                raise OutputError(f"cannot write {p}: the file is read-only")
        _probe_folder(p.parent, p)


def check_writable_folder(folder: str | Path) -> None:
    """Raise :class:`OutputError` unless ``folder`` is (or can be created as) a folder in
    which files can be written."""
    f = Path(folder)
    if f.exists() and not f.is_dir():
        raise OutputError(f"output folder {f} is a file; give a folder name")
    _probe_folder(f, f)


def file_mode() -> int:
    """The mode a new file gets under the current umask (mkstemp makes 0600 files)."""
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def write_files(files: Iterable[tuple[str | Path, bytes]]) -> None:
    """Write each ``(path, data)`` whole, all or none: temporary files beside the targets
    first, then renamed into place. Only a regular file (or a new path) is replaced; anything
    else that exists (a device such as /dev/null, a FIFO) is written to, after the others.
    An OSError becomes :class:`OutputError`; any failure or interruption removes the
    temporary files."""
    files = [(Path(p), data) for p, data in files]
    check_writable(p for p, _ in files)
    pending: list[tuple[str, Path]] = []
    devices = []
    try:
        for p, data in files:
            if p.exists() and not p.is_file():
                devices.append((p, data))
                continue
            p.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=_PREFIX, dir=p.parent)
            pending.append((tmp, p))
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.chmod(tmp, file_mode())
        while pending:
            tmp, p = pending[0]
            os.replace(tmp, p)
            pending.pop(0)
        for p, data in devices:
            with open(p, "wb") as f:
                f.write(data)
    except OSError as exc:
        where = getattr(exc, "filename", None) or ""
        raise OutputError(f"cannot write {where or 'the output'}: {_reason(exc)}") from None
    finally:
        for tmp, _ in pending:
            if os.path.exists(tmp):
                os.unlink(tmp)


def write_file(path: str | Path, data: bytes) -> None:
    """:func:`write_files` for one file."""
    write_files([(path, data)])
