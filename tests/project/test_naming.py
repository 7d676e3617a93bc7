"""Files, tests and documentation are named by concept, never by issue number: a reader who does
not know the project's issue tracker must still find what a test checks and where a topic is."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("fpucore", "app", "tests", "benchmarks", "docs")
DOCS = ("README.md", "benchmarks/README.md")
# "issue14", "issue_14", "issue-14", "Issue 14", "issues 13 and 14", "#14" after "issue"
BY_ISSUE = re.compile(r"issues?[ _\-#]*\d", re.I)
BY_DEFECT = re.compile(r"defects?", re.I)


def _paths() -> list[Path]:
    out: list[Path] = []
    for folder in FOLDERS:
        out += [
            p
            for p in (ROOT / folder).rglob("*")
            if "__pycache__" not in p.parts and ".numba_cache" not in p.parts
        ]
    return out


def test_no_file_or_folder_is_named_by_issue_number():
    bad = [
        str(p.relative_to(ROOT))
        for p in _paths()
        if BY_ISSUE.search(p.name) or BY_DEFECT.search(p.name)
    ]
    assert not bad, "named by issue, not by concept: " + ", ".join(bad)


def test_no_test_function_or_class_is_named_by_issue_number():
    bad = []
    for path in sorted((ROOT / "tests").rglob("test_*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                if BY_ISSUE.search(node.name) or BY_DEFECT.search(node.name):
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.name}")
    assert not bad, "tests named by issue, not by concept:\n" + "\n".join(bad)


def test_readmes_name_no_issue_numbers():
    """Neither a heading nor a sentence of the README or the benchmarks' README points to an
    issue: a section is found by its topic, and a figure's history lives in git log."""
    bad = []
    for name in DOCS:
        for k, line in enumerate((ROOT / name).read_text().splitlines(), 1):
            if BY_ISSUE.search(line):
                bad.append(f"{name}:{k}: {line.strip()[:80]}")
    assert not bad, "issue numbers in the documentation:\n" + "\n".join(bad)


def test_the_checks_catch_what_they_are_for():
    """The patterns find the names this test exists to keep out (so it can fail)."""
    for name in ("test_cli_issue14.py", "test_issue14_validation.py", "README (issue 13)"):
        assert BY_ISSUE.search(name), name
    assert BY_DEFECT.search("test_app_defects.py")
    for name in ("test_tissue.py", "test_issues_page.py", "test_decision.py", "issuer"):
        assert not BY_ISSUE.search(name), name
