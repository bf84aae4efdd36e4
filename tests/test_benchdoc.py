"""scripts/benchdoc.py: a benchmark script's table goes into its own marked section of a doc,
replacing only that section."""

from __future__ import annotations

import sys

from tests import ROOT

sys.path.insert(0, str(ROOT / "scripts"))

from benchdoc import command_line, write_section  # noqa: E402


def test_a_section_is_added_then_replaced_and_the_rest_of_the_doc_stays(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text("# Benchmarks\n\nHow to read them.\n", encoding="utf-8")
    kw = dict(doc=doc, machine_line="a CPU, 2 cores", date="2020-01-02")
    write_section("one", "| a |\n|---|\n| 1 |", "python scripts/one.py --x 1", **kw)
    write_section("two", "| b |\n|---|\n| 2 |", "python scripts/two.py", **kw)
    write_section("one", "| a |\n|---|\n| 3 |", "python scripts/one.py --x 3", **kw)
    text = doc.read_text(encoding="utf-8")
    assert text.startswith("# Benchmarks\n\nHow to read them.\n")
    assert text.count("<!-- one -->") == 1 and text.count("<!-- /one -->") == 1
    one = text[text.index("<!-- one -->"):text.index("<!-- /one -->")]
    assert "| 3 |" in one and "| 1 |" not in one and "`python scripts/one.py --x 3`" in one
    assert "a CPU, 2 cores; 2020-01-02." in one
    assert text.index("<!-- /one -->") < text.index("<!-- two -->")  # replaced in place
    assert "| 2 |" in text[text.index("<!-- two -->"):]


def test_the_command_is_as_typed_from_the_root_without_write_docs():
    argv = [str(ROOT / "scripts" / "bench_app.py"), "--sizes", "160x48", "--write-docs",
            "--load", "2"]
    assert command_line(argv) == "python scripts/bench_app.py --sizes 160x48 --load 2"
