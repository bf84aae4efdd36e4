"""The docs: generated files current, command outputs real, links alive, the README's promises.

The generated files are the same on every supported Python: docs/reference/cli.md is laid out
by scripts/gen_docs.py from the parser's actions, not by argparse's help formatter (whose
layout changed in Python 3.13), so this test runs unchanged on 3.11 and 3.13.
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
import unicodedata

from tests import ROOT

sys.path.insert(0, str(ROOT / "scripts"))
import gen_docs  # noqa: E402

#: a link to a doc another branch writes (scripts/bench_app.py writes docs/benchmarks.md)
WRITTEN_ELSEWHERE = {"docs/benchmarks.md"}


def test_generated_docs_are_current():
    r = subprocess.run([sys.executable, "scripts/gen_docs.py", "--check"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_cli_reference_is_not_argparse_help():
    # the layout is gen_docs.py's own: no "options:" block, whose spacing differs by version
    text = (ROOT / "docs/reference/cli.md").read_text(encoding="utf-8")
    assert "options:" not in text and "usage:" not in text
    assert "- `--theta-i DEG [DEG ...]` (required): incidence angles θi" in text


def test_every_key_is_in_the_keys_reference():
    from tuibrdf.app.keys import KEYS

    text = (ROOT / "docs/reference/keys.md").read_text(encoding="utf-8")
    for k in KEYS:
        first = k.keys.split(",")[0]
        assert f"`{gen_docs._key_name(first)}`" in text, k


def test_readme_opens_with_the_two_commands():
    lines = [ln for ln in (ROOT / "README.md").read_text().splitlines() if ln.strip()]
    code = [ln for ln in lines[:6] if "pip install" in ln]
    assert any(ln.startswith("pip install -e . && tuibrdf ") for ln in code)
    assert any(ln.startswith("pip install -e '.[test]' && python -m pytest ") for ln in code)


def test_readme_picture_is_small():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    pictures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert pictures == ["docs/images/viewer.png"]
    png = (ROOT / pictures[0]).read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) < 64 * 1024


def test_readme_keys_exist():
    # every key the README's table names is a key of the viewer
    from tuibrdf.app.keys import KEYS

    names = {gen_docs._key_name(n) for k in KEYS for n in k.keys.split(",")}
    names |= {n.split("+")[-1] for n in names}  # "shift+←" also stands for "←"
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    table = text.split("| keys |", 1)[1].split("\n\n", 1)[0]
    for row in table.splitlines()[2:]:
        cell = row.split("|")[1]
        shown = re.findall(r"`([^`]+)`", cell) + re.findall(r"[←→↑↓]", cell)
        shown += ["Enter"] if "Enter" in cell else []
        for key in shown:
            assert key in names, f"README key {key!r} is not in tuibrdf/app/keys.py"


def test_guide_pictures_are_small():
    # the guide stays readable: every picture at most 64 columns by 20 rows
    text = (ROOT / "docs/guide.md").read_text(encoding="utf-8")
    renders = [c for c in gen_docs.commands_in(text) if c.startswith("tuibrdf render ")]
    assert len(renders) >= 10
    for line in renders:
        args = shlex.split(line)
        assert "--color" in args and args[args.index("--color") + 1] == "none", line
        width = int(args[args.index("--width") + 1])
        height = int(args[args.index("--height") + 1])
        assert width <= 64 and height <= 20, line
        assert "--view" not in args or args[args.index("--view") + 1] != "all", line


def _anchors(md: str) -> set[str]:
    """GitHub's anchors of a Markdown file's headings."""
    out = set()
    for line in md.splitlines():
        m = re.match(r"#{1,6} (.*)", line)
        if m:
            title = m.group(1).strip().lower().replace("`", "")
            slug = "".join(c for c in title
                           if c in " -_" or unicodedata.category(c)[0] in "LN")
            out.add(slug.replace(" ", "-"))
    return out


def test_links_resolve():
    # every relative link of the README and docs/ names a file that exists, and a heading
    # of it when it has an anchor
    files = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    bad = []
    for path in files:
        text = path.read_text(encoding="utf-8")
        text = re.sub(r"```.*?```", "", text, flags=re.S)  # not in code blocks
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue
            file, _, anchor = target.partition("#")
            dest = (path.parent / file).resolve() if file else path
            rel = dest.relative_to(ROOT).as_posix() if dest.is_relative_to(ROOT) else str(dest)
            if not dest.exists():
                if rel not in WRITTEN_ELSEWHERE:
                    bad.append(f"{path.relative_to(ROOT)}: {target}")
                continue
            if anchor and dest.suffix == ".md" and \
                    anchor not in _anchors(dest.read_text(encoding="utf-8")):
                bad.append(f"{path.relative_to(ROOT)}: {target} (no such heading)")
    assert not bad, bad


def test_no_doc_points_at_a_deleted_doc():
    # docstrings, comments and messages name docs that exist (docs/benchmarks.md aside)
    pattern = re.compile(r"docs/[\w/.-]+\.md")
    bad = []
    for path in [*ROOT.glob("tuibrdf/**/*.py"), *ROOT.glob("tuibrdf/**/*.md"),
                 *ROOT.glob("scripts/*.py"), *ROOT.glob("tests/**/*.py")]:
        for ref in pattern.findall(path.read_text(encoding="utf-8")):
            if not (ROOT / ref).exists() and ref not in WRITTEN_ELSEWHERE:
                bad.append(f"{path.relative_to(ROOT)}: {ref}")
    assert not bad, bad
