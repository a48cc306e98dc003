"""Every trick that patches a dependency or the interpreter (checker/plumbing) still finds
what it patches in the installed releases: a release that renames or drops it fails here,
loudly, instead of a silent slowdown, a report laid out otherwise or figures without their
recorded text. Each module states the releases it was measured on (``MEASURED_ON``)."""

from __future__ import annotations

import importlib

import pytest

TRICKS = ("frame_stack", "gc_tuning", "pdf_compression", "pdf_engine_import",
          "matplotlib_patches")


@pytest.mark.parametrize("name", TRICKS)
def test_the_trick_states_the_releases_it_was_measured_on(name):
    mod = importlib.import_module(f"checker.plumbing.{name}")
    assert any(ch.isdigit() for ch in mod.MEASURED_ON), mod.MEASURED_ON


@pytest.mark.parametrize("name", TRICKS)
def test_the_installed_releases_have_what_the_trick_patches(name):
    mod = importlib.import_module(f"checker.plumbing.{name}")
    assert mod.missing_targets() == [], (
        f"checker.plumbing.{name}: the installed release no longer has what the trick"
        f" patches: {mod.missing_targets()} (measured on {mod.MEASURED_ON}); update or drop it")


def test_a_missing_target_is_named(monkeypatch):
    import zlib

    import matplotlib.artist
    import matplotlib.backends.backend_agg  # noqa: F401  # its artists built before kwdoc goes
    import pydyf

    from checker.plumbing import matplotlib_patches, pdf_compression

    # missing_targets imports the Agg backend: imported first in this process without kwdoc,
    # its artist classes (Line2D...) would fail half-built and break matplotlib for every
    # later test in the same worker
    monkeypatch.delattr(matplotlib.artist, "kwdoc")
    assert matplotlib_patches.missing_targets() == ["matplotlib.artist.kwdoc"]
    monkeypatch.setattr(pydyf, "zlib", None)
    assert pdf_compression.missing_targets() == ["pydyf.zlib (the zlib module)"]
    assert zlib.compress(b"x")  # the real module untouched
