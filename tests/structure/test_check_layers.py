#!/usr/bin/env python3
"""The layer check itself (scripts/check_layers.py), on small planted trees.

A clean three-layer tree must pass in enforce mode; the same tree with one planted
upward include, one sideways include, or a planted cycle must fail and name the
offending file and line; report mode must print the same findings and exit 0; a file no
component owns is a map error (exit 2) in either mode. The expected findings follow from
the planted includes, not from running the checker.
"""
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "check_layers.py")

LAYERS = textwrap.dedent("""\
    mode = "enforce"
    [[layer]]
    name = "core"
    components = { core = ["core"] }
    [[layer]]
    name = "models"
    components = { surface = ["surface"], tribology = ["tribology"] }
    [[layer]]
    name = "pipeline"
    components = { pipeline = ["pipeline", "surface/examine.hpp"] }
    """)

CLEAN = {
    "core/error.hpp": "#pragma once\n",
    "core/error.cpp": '#include "core/error.hpp"\n',
    "surface/asperity.hpp": '#pragma once\n#include "core/error.hpp"\n#include <vector>\n',
    "tribology/model.hpp": '#pragma once\n#include "core/error.hpp"\n',
    "tribology/model.cpp": '#include "model.hpp"\n#include "core/error.hpp"\n',  # beside-the-file form
    "pipeline/run.hpp": '#pragma once\n#include "surface/asperity.hpp"\n#include "tribology/model.hpp"\n',
    # Owned by pipeline although it sits in surface/ (the longest path wins), so it may
    # include both models.
    "surface/examine.hpp": '#pragma once\n#include "surface/asperity.hpp"\n#include "tribology/model.hpp"\n',
}


class LayerCheckTest(unittest.TestCase):
    def check(self, files, mode=None, layers=LAYERS):
        with tempfile.TemporaryDirectory() as src:
            for path, text in files.items():
                os.makedirs(os.path.join(src, os.path.dirname(path)), exist_ok=True)
                with open(os.path.join(src, path), "w") as f:
                    f.write(text)
            with open(os.path.join(src, "layers.toml"), "w") as f:
                f.write(layers)
            command = [sys.executable, SCRIPT, "--src", src] + (["--mode", mode] if mode else [])
            done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            return done.returncode, done.stdout

    def planted(self, **changes):
        files = dict(CLEAN)
        files.update(changes)
        return files

    def test_clean_tree_passes_enforce(self):
        status, out = self.check(CLEAN)
        self.assertEqual(status, 0, out)
        self.assertIn("summary: upward 0, sideways 0, component cycles 0 (two-way pairs 0), file cycles 0", out)

    def test_planted_upward_edge_fails_with_file_and_line(self):
        files = self.planted(**{"core/error.cpp": '#include "core/error.hpp"\n\n#include "pipeline/run.hpp"\n'})
        status, out = self.check(files)
        self.assertEqual(status, 1, out)
        self.assertIn("upward edges: 1 include(s) between 1 component pair(s)", out)
        self.assertIn("core/error.cpp:3 -> pipeline/run.hpp", out)
        # core -> pipeline -> {surface, tribology} -> core is also a cycle of components.
        self.assertIn("component cycles: 1 group(s)", out)

    def test_include_relative_to_the_file_is_followed(self):
        files = self.planted(**{"surface/asperity.cpp": '#include "asperity.hpp"\n#include "../pipeline/run.hpp"\n'})
        status, out = self.check(files)
        self.assertEqual(status, 1, out)
        self.assertIn("surface/asperity.cpp:2 -> pipeline/run.hpp", out)
        self.assertIn("upward edges: 1 include(s)", out)

    def test_planted_sideways_edge_fails(self):
        files = self.planted(**{"tribology/model.hpp": '#pragma once\n#include "surface/asperity.hpp"\n'})
        status, out = self.check(files)
        self.assertEqual(status, 1, out)
        self.assertIn("sideways edges: 1 include(s)", out)
        self.assertIn("tribology/model.hpp:2 -> surface/asperity.hpp", out)
        self.assertIn("component cycles: 0 group(s)", out)

    def test_planted_cycle_between_components_fails(self):
        # surface <-> tribology through two headers: both sideways, and a two-way pair.
        files = self.planted(**{
            "tribology/model.hpp": '#pragma once\n#include "surface/asperity.hpp"\n',
            "surface/asperity.hpp": '#pragma once\n#include "tribology/model.hpp"\n',
        })
        status, out = self.check(files)
        self.assertEqual(status, 1, out)
        self.assertIn("component cycles: 1 group(s); 1 pair(s) of components include each other", out)
        self.assertIn("group {surface, tribology}", out)
        self.assertIn("surface <-> tribology", out)

    def test_planted_file_cycle_within_a_component_fails(self):
        files = self.planted(**{
            "core/a.hpp": '#pragma once\n#include "core/b.hpp"\n',
            "core/b.hpp": '#pragma once\n#include "core/c.hpp"\n',
            "core/c.hpp": '#pragma once\n#include "core/a.hpp"\n',
        })
        status, out = self.check(files)
        self.assertEqual(status, 1, out)
        self.assertIn("file cycles: 1", out)
        self.assertIn("core/a.hpp -> core/b.hpp -> core/c.hpp -> core/a.hpp", out)

    def test_report_mode_prints_but_passes(self):
        files = self.planted(**{"core/error.cpp": '#include "pipeline/run.hpp"\n'})
        status, out = self.check(files, mode="report")
        self.assertEqual(status, 0, out)
        self.assertIn("core/error.cpp:1 -> pipeline/run.hpp", out)
        self.assertIn("report mode:", out)

    def test_a_file_no_component_owns_is_a_map_error(self):
        files = self.planted(**{"inverse/fit.cpp": '#include "core/error.hpp"\n'})
        for mode in ("report", "enforce"):
            status, out = self.check(files, mode=mode)
            self.assertEqual(status, 2, out)
            self.assertIn("no component owns inverse/fit.cpp", out)

    def test_an_include_outside_src_is_not_an_edge(self):
        # A quoted include that resolves to no file of src/ (a generated or third-party
        # header) cannot be placed in a layer and is left alone.
        files = self.planted(**{"core/error.cpp": '#include "core/error.hpp"\n#include "build_info.cpp"\n'})
        status, out = self.check(files)
        self.assertEqual(status, 0, out)


if __name__ == "__main__":
    unittest.main()
