"""A normal (non-editable) install works (issue 21, item 13): the built wheel holds every
package (found automatically, checker.study included) and the rule and template data;
installed into a fresh virtual environment it runs every subcommand's ``--help`` and
``checker rules`` from a folder outside the source tree.

The fresh environment gets the dependencies of the running interpreter through a ``.pth``
line (no download); paths added that way do not run their own ``.pth`` files, so the
editable install of the development environment stays invisible and ``checker`` is imported
from the wheel (asserted)."""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
COMMANDS = ("template", "check", "report", "study", "compare", "rules")

pytestmark = pytest.mark.ci


def _run(args, cwd, **kw):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    return subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          env=env, timeout=600, **kw)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    d = tmp_path_factory.mktemp("wheel")
    r = _run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q",
              "--wheel-dir", d / "dist"], cwd=d)
    assert r.returncode == 0, r.stdout + r.stderr
    (wheel,) = (d / "dist").glob("checker-*.whl")
    venv = d / "venv"
    r = _run([sys.executable, "-m", "venv", venv], cwd=d)
    assert r.returncode == 0, r.stderr
    py = venv / "bin" / "python"
    r = _run([py, "-m", "pip", "install", "--no-deps", "-q", wheel], cwd=d)
    assert r.returncode == 0, r.stdout + r.stderr
    site = Path(_run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                     cwd=d).stdout.strip())
    deps = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}
    (site / "_checker_test_deps.pth").write_text("\n".join(sorted(deps)) + "\n")
    return wheel, venv, d


def test_wheel_holds_every_package_and_the_data(installed):
    wheel, _, _ = installed
    names = set(zipfile.ZipFile(wheel).namelist())
    src = {p.parent.relative_to(ROOT).as_posix() for p in (ROOT / "checker").rglob("*.py")
           if "__pycache__" not in p.parts}
    for pkg in sorted(src):
        assert f"{pkg}/__init__.py" in names, f"{pkg} is missing from the wheel"
    assert "checker/study/run.py" in names
    assert {f"checker/_rules/{p.name}" for p in (ROOT / "rules").glob("*.toml")} <= names
    assert {f"checker/_templates/{p.name}" for p in (ROOT / "templates").iterdir()} <= names
    assert "checker/calc/data/reynolds_map.npz" in names
    assert "checker/calc/data/throw_stiffness.json" in names
    assert "checker/calc/data/throw_stiffness_fe.csv" in names


def test_installed_commands_run_from_outside_the_source_tree(installed, tmp_path):
    _, venv, _ = installed
    py, exe = venv / "bin" / "python", venv / "bin" / "checker"
    r = _run([py, "-c", "import checker; print(checker.__file__)"], cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert Path(r.stdout.strip()).resolve().is_relative_to(venv.resolve()), r.stdout
    r = _run([exe, "--help"], cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    for cmd in COMMANDS:
        assert cmd in r.stdout, (cmd, r.stdout)
        r2 = _run([exe, cmd, "--help"], cwd=tmp_path)
        assert r2.returncode == 0 and "Usage:" in r2.stdout, (cmd, r2.stderr)
    r = _run([exe, "rules"], cwd=tmp_path)
    assert r.returncode == 0 and "JNT-001" in r.stdout, r.stderr
    r = _run([exe, "template", "e.xlsx"], cwd=tmp_path)
    assert r.returncode == 0 and (tmp_path / "e.xlsx").is_file(), r.stderr
