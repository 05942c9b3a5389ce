#!/usr/bin/env python3
"""The documentation link check (scripts/check_doc_links.py) on a small planted tree: a
link out of the repository, to a missing file, or to a missing anchor is reported with
its file and line; good links, web addresses and code spans are not. The expected
findings follow from the planted links, not from running the checker.
"""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import check_doc_links  # noqa: E402

MODEL = """# The model

<a id="model-1"></a>
### 1.2 Model 1: Coulomb stick-slip

## Spectra and identifiability
## Spectra and identifiability
"""


class DocLinksTest(unittest.TestCase):
    def problems(self, readme):
        with tempfile.TemporaryDirectory() as root:
            os.makedirs(os.path.join(root, "repo", "docs"))
            with open(os.path.join(root, "repo", "docs", "model.md"), "w") as f:
                f.write(MODEL)
            with open(os.path.join(root, "outside.md"), "w") as f:
                f.write("# outside\n")
            path = os.path.join(root, "repo", "README.md")
            with open(path, "w") as f:
                f.write(readme)
            return check_doc_links.check(path, root=os.path.join(root, "repo"))

    def test_good_links_pass(self):
        readme = ("[model](docs/model.md) [m1](docs/model.md#model-1) "
                  "[heading](docs/model.md#12-model-1-coulomb-stick-slip) "
                  "[repeat](docs/model.md#spectra-and-identifiability-1) [self](#top)\n"
                  "<a id=\"top\"></a> [web](https://example.org/x) `[code](../nowhere.md)`\n"
                  "```\n[fenced](../nowhere.md)\n```\n")
        self.assertEqual(self.problems(readme), [])

    def test_link_out_of_the_repository(self):
        self.assertEqual(self.problems("text\n[model](../outside.md)\n"),
                         ["README.md:2: (../outside.md) leaves the repository"])

    def test_missing_file_and_anchor(self):
        problems = self.problems("[a](docs/methods.md) [b](docs/model.md#model-9)\n")
        self.assertEqual(problems, ["README.md:1: (docs/methods.md) names a file that does not exist",
                                    "README.md:1: (docs/model.md#model-9) names no anchor of docs/model.md"])


if __name__ == "__main__":
    unittest.main()
