"""``docs/rules.md`` is generated from the rule table (``scripts/make_rules_doc.py``) and is
up to date: after a change of ``rules/*.toml`` run ``python scripts/make_rules_doc.py``."""

from __future__ import annotations

import importlib.util
from pathlib import Path

from checker.evaluation.ruletable import load_rules

ROOT = Path(__file__).resolve().parents[1]


def _script():
    spec = importlib.util.spec_from_file_location("make_rules_doc",
                                                  ROOT / "scripts" / "make_rules_doc.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_committed_rules_doc_is_up_to_date():
    committed = (ROOT / "docs" / "rules.md").read_text(encoding="utf-8")
    assert _script().rules_doc() == committed, "run python scripts/make_rules_doc.py"


def test_every_rule_with_its_quantity_module_limit_and_source():
    text = (ROOT / "docs" / "rules.md").read_text(encoding="utf-8")
    for r in load_rules().rules:
        section = text.split(f"### {r.id}\n", 1)[1].split("\n### ", 1)[0]
        assert f"`{r.quantity}`" in section, r.id
        assert "module `" in section, r.id
        assert f"- Limit: {r.limit_text()}" in section, r.id
        assert f"- Source: {r.source}" in section, r.id


def test_render_of_a_small_table(tmp_path):
    (tmp_path / "joints.toml").write_text(
        '# Joints: a test file.\n#\n# Second paragraph.\n\n[[rule]]\nid = "JNT-901"\n'
        'name = "Cover factor | test"\nquantity = "joint.cover_factor"\ncheck = ">="\n'
        'limit = 1.8\nunit = ""\nseverity = "error"\nsource = "VDI 2230"\n'
        'rationale = "Slip."\n', encoding="utf-8")
    text = _script().render(load_rules(tmp_path), tmp_path)
    assert "| [JNT-901](#jnt-901) | Cover factor \\| test | error | ≥ 1.8 | `joints` |" in text
    assert "Joints: a test file.\n\nSecond paragraph." in text
    assert "- Computed by: Bolted joints: module `joints`" in text
    assert "- Source: VDI 2230" in text
