"""docs/python.md cannot rot: docs/python_example.py runs (from the repository's root, as
its first line says), and the page shows each of its cells verbatim, each followed by the
output that cell prints now."""
import os
import re

from conftest import SOURCE_DIR, source
from example_cells import cells, outputs

BLOCK = re.compile(r"^```(python|text)\n(.*?)^```$", re.MULTILINE | re.DOTALL)


def test_the_page_shows_every_cell_and_its_output():
    script = open(source("docs", "python_example.py")).read()
    page = open(source("docs", "python.md")).read()
    # The walk-through: alternating python and text blocks after its heading.
    walk = page[page.index("## Walk-through"):]
    blocks = BLOCK.findall(walk)
    os.chdir(SOURCE_DIR)
    printed = outputs(script, source("docs", "python_example.py"))
    expected = []
    for (_, code), text in zip(cells(script), printed):
        expected += [("python", code + "\n"), ("text", text)]
    assert len(blocks) == len(expected), f"docs/python.md shows {len(blocks) // 2} cells, the script has {len(expected) // 2}"
    for (kind, shown), (want_kind, want) in zip(blocks, expected):
        assert kind == want_kind and shown == want, f"docs/python.md shows\n{shown}\nbut the script's cell is/prints\n{want}"
