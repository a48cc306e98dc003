"""Locate the project's data folders (``rules/`` and ``templates/``).

In a source checkout or an editable install they sit next to the package; a regular (wheel)
install maps them to the packages ``checker._rules`` and ``checker._templates``.
"""

from __future__ import annotations

import importlib.util
from importlib import resources
from pathlib import Path

_ROOT = Path(__file__).resolve().parents[2]


def _find(folder: str, package: str) -> Path:
    local = _ROOT / folder
    if local.is_dir():
        return local
    # the data packages have no __init__.py (namespace packages): files() would give a
    # MultiplexedPath, whose str() is not a path; the package's folder is the first location
    spec = importlib.util.find_spec(package)
    if spec is not None and spec.submodule_search_locations:
        return Path(next(iter(spec.submodule_search_locations)))
    return Path(str(resources.files(package)))


def rules_dir() -> Path:
    """Folder of the default rule table (``*.toml``)."""
    return _find("rules", "checker._rules")


def templates_dir() -> Path:
    """Folder of the report templates and CSS."""
    return _find("templates", "checker._templates")
