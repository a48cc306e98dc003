"""The README is what a new user reads first (issue 37 item 13): under 15 kB, its first two
commands the set-up and the tests, every docs/ page it names present; the details live in
docs/, whose pages link to each other without dead ends."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
MAX_BYTES = 15_000


def _docs_links(text: str) -> set[str]:
    """Every docs/ path the text names: Markdown link targets and paths in the prose."""
    links = set(re.findall(r"\]\((docs/[^)#\s]*)", text))
    links |= set(re.findall(r"(?<![\w/.])(docs/[\w./-]+\.md)", text))
    return links


def test_readme_is_short():
    size = len(README.read_bytes())
    assert size < MAX_BYTES, f"README.md is {size} bytes; move details to docs/"


def test_readme_first_two_commands_are_setup_and_tests():
    blocks = re.findall(r"```(\w*)\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)
    assert [b.strip() for _, b in blocks[:2]] == [
        "bash setup.sh", ".venv/bin/python -m pytest -q -n auto"]


def test_every_docs_link_of_the_readme_resolves():
    links = _docs_links(README.read_text(encoding="utf-8"))
    assert len(links) >= 8  # the README points to the details
    missing = sorted(x for x in links if not (ROOT / x).exists())
    assert not missing, missing
    for page in ("docs/benchmarks.md", "docs/examples.md", "docs/methods.md",
                 "docs/outputs.md", "docs/studies.md", "docs/workbook.md", "docs/rules.md"):
        assert page in links, page


def test_links_between_docs_pages_resolve():
    for page in sorted((ROOT / "docs").glob("*.md")):
        text = page.read_text(encoding="utf-8")
        for target in re.findall(r"\]\(([^)#\s]+\.md)(?:#[^)]*)?\)", text):
            if "://" in target:
                continue
            assert (page.parent / target).resolve().exists(), (page.name, target)


def test_benchmark_history_is_one_section_to_append_to():
    """Speed rounds are appended to docs/benchmarks.md as ### sections under '## History'
    (simple to merge); the history moved there from the README."""
    text = (ROOT / "docs" / "benchmarks.md").read_text(encoding="utf-8")
    heads = re.findall(r"^(#{1,6}) (.*)$", text, flags=re.M)
    assert heads[0] == ("#", "Benchmarks: run time against error")
    assert [h for h in heads if h[0] == "##"] == [("##", "History")]
    rounds = [t for lvl, t in heads if lvl == "###"]
    assert "Check speed (issue 25)" in rounds and "Report and check: time per stage" in rounds
