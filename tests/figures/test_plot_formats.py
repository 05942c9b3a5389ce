#!/usr/bin/env python3
"""`stengmc plot --figure-format png|pdf|svg --dpi N` through the command line, on a run file
the paper studies left (argv[1]: that file; STENGMC_BINARY: the binary).

Each format is written under its own extension and is what it says (a PDF starts %PDF,
an SVG holds <svg, a PNG has the PNG signature); --dpi 300 gives a PNG twice as wide as
the default 150; an unknown format and a dpi outside 20..1200 are refused with exit 2,
naming the option, and write nothing. Debian's python3-pil."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

from PIL import Image

BINARY = os.environ.get("STENGMC_BINARY", "stengmc")
SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else ""


class PlotFormatsTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.run_file = os.path.join(self.folder, "run.h5")
        shutil.copy(SOURCE, self.run_file)

    def tearDown(self):
        shutil.rmtree(self.folder)

    def plot(self, *options):
        return subprocess.run([BINARY, "plot", self.run_file, *options], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)

    def figure(self, extension):
        return os.path.join(self.folder, "run." + extension)

    def test_each_format_is_what_its_extension_says(self):
        for extension, starts in (("pdf", b"%PDF"), ("svg", None), ("png", b"\x89PNG")):
            done = self.plot("--figure-format", extension)
            self.assertEqual(done.returncode, 0, done.stdout)
            with open(self.figure(extension), "rb") as f:
                head = f.read(4096)
            if starts:
                self.assertTrue(head.startswith(starts), extension)
            else:
                self.assertIn(b"<svg", head)

    def test_dpi_scales_the_png(self):
        self.assertEqual(self.plot().returncode, 0)
        with Image.open(self.figure("png")) as image:
            default = image.size
        self.assertEqual(self.plot("--dpi", "300").returncode, 0)
        with Image.open(self.figure("png")) as image:
            self.assertAlmostEqual(image.size[0] / default[0], 2.0, delta=0.01)

    def test_bad_options_are_refused(self):
        for options, named in ((["--figure-format", "jpg"], "--figure-format"), (["--dpi", "5"], "--dpi"),
                               (["--dpi", "5000"], "--dpi")):
            done = self.plot(*options)
            self.assertEqual(done.returncode, 2, done.stdout)
            self.assertIn(named, done.stdout)
        self.assertEqual(sorted(os.listdir(self.folder)), ["run.h5"])


if __name__ == "__main__":
    unittest.main()
