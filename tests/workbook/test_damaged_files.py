"""Damaged and hostile .xlsx files: one clean file-level input error naming the file (exit 2),
never an internal error or a traceback, whatever openpyxl, zipfile or the XML parser raise."""

from __future__ import annotations

import struct
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import example_path

SHEET = "xl/worksheets/sheet2.xml"


def _rezip(src: Path, dst: Path, change) -> Path:
    """Copy the zip ``src`` to ``dst`` with ``change(name, data) -> data | None`` per member."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = change(info.filename, zin.read(info.filename))
            if data is not None:
                zout.writestr(info, data)
    return dst


def _corrupt_member(src: Path, dst: Path) -> Path:
    """Flip bytes inside the compressed data of one worksheet (bad CRC / bad deflate stream)."""
    blob = bytearray(src.read_bytes())
    with zipfile.ZipFile(src) as z:
        info = z.getinfo(SHEET)
    name_len, extra_len = struct.unpack("<HH", blob[info.header_offset + 26:
                                                     info.header_offset + 30])
    start = info.header_offset + 30 + name_len + extra_len
    for k in range(start + info.compress_size // 3, start + info.compress_size // 3 + 40):
        blob[k] ^= 0x5A
    dst.write_bytes(bytes(blob))
    return dst


def _encrypted_member(src: Path, dst: Path) -> Path:
    """Set the 'encrypted' flag of one member (local and central headers)."""
    blob = bytearray(src.read_bytes())
    with zipfile.ZipFile(src) as z:
        info = z.getinfo(SHEET)
    blob[info.header_offset + 6] |= 0x01  # local file header: general purpose flags
    # this member's central directory entry, found by its name
    pos = blob.find(b"PK\x01\x02")
    while pos != -1:
        n = struct.unpack("<H", blob[pos + 28:pos + 30])[0]
        if blob[pos + 46:pos + 46 + n] == SHEET.encode():
            blob[pos + 8] |= 0x01
            break
        pos = blob.find(b"PK\x01\x02", pos + 4)
    assert pos != -1
    dst.write_bytes(bytes(blob))
    return dst


def _cases(tmp_path: Path) -> dict[str, Path]:
    good = example_path(tmp_path, "good.xlsx")
    size = good.stat().st_size
    out = {
        "corrupt member": _corrupt_member(good, tmp_path / "corrupt.xlsx"),
        "encrypted member": _encrypted_member(good, tmp_path / "encrypted.xlsx"),
        "truncated sheet XML": _rezip(good, tmp_path / "truncated.xlsx",
                                      lambda n, d: d[: len(d) // 2] if n == SHEET else d),
        "sheet XML garbage": _rezip(good, tmp_path / "garbage.xlsx",
                                    lambda n, d: b"\x00\xff<<not xml" if n == SHEET else d),
        "missing workbook part": _rezip(good, tmp_path / "noworkbook.xlsx",
                                        lambda n, d: None if n == "xl/workbook.xml" else d),
        "missing sheet part": _rezip(good, tmp_path / "nosheet.xlsx",
                                     lambda n, d: None if n == SHEET else d),
        "truncated file": tmp_path / "cut.xlsx",
        "zip that is not a workbook": tmp_path / "other.xlsx",
        "encrypted workbook (OLE)": tmp_path / "ole.xlsx",
        "empty file": tmp_path / "empty.xlsx",
    }
    out["truncated file"].write_bytes(good.read_bytes()[: size // 2])
    with zipfile.ZipFile(out["zip that is not a workbook"], "w") as z:
        z.writestr("readme.txt", "hello")
    out["encrypted workbook (OLE)"].write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + bytes(600))
    out["empty file"].write_bytes(b"")
    return out


@pytest.fixture(scope="module")
def damaged(tmp_path_factory) -> dict[str, Path]:
    return _cases(tmp_path_factory.mktemp("damaged"))


CASES = ["corrupt member", "encrypted member", "truncated sheet XML", "sheet XML garbage",
         "missing workbook part", "missing sheet part", "truncated file",
         "zip that is not a workbook", "encrypted workbook (OLE)", "empty file"]


@pytest.mark.parametrize("case", CASES)
def test_damaged_file_is_one_clean_file_level_error(damaged, case):
    path = damaged[case]
    before = path.read_bytes()
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    errs = info.value.errors
    assert len(errs) == 1, errs
    assert errs[0].where == path.name
    assert "cannot be read: not an Excel .xlsx workbook" in errs[0].message
    r = CliRunner().invoke(main, ["check", str(path), "--format", "json"])
    assert r.exit_code == 2, r.output
    assert r.stdout == ""
    assert path.name in r.stderr and "cannot be read" in r.stderr
    assert "Traceback" not in r.output and "internal error" not in r.output.lower()
    assert path.read_bytes() == before


def test_encrypted_workbook_says_so(damaged):
    with pytest.raises(InputErrors, match="encrypted .password-protected. workbook"):
        load_engine(damaged["encrypted workbook (OLE)"])


def test_the_undamaged_copy_reads(tmp_path):
    assert load_engine(example_path(tmp_path)).name
