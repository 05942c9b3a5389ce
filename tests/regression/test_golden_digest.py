#!/usr/bin/env python3
"""The golden-digest tool itself: it must see a one-ulp change anywhere in a result and
must not see what records when or how fast a file was made (scripts/golden_digest.py).

Each case writes two small HDF5 files that differ in one thing and compares their digest
lines; the expected outcome (changed or not) follows from the tool's documented rule, not
from running the tool.
"""
import os
import sys
import tempfile
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import golden_digest  # noqa: E402


def write(path, voltage, attributes=None, kinds=("stick", "slip"), dtype="<f8"):
    with h5py.File(path, "w") as f:
        f.attrs["created_utc"] = "2026-01-01T00:00:00Z"
        f.attrs["git_revision"] = "abc"
        f.attrs["seed"] = 7
        f.attrs["title"] = "a title"
        for name, value in (attributes or {}).items():
            f.attrs[name] = value
        circuit = f.create_group("circuit")
        circuit.create_dataset("voltage", data=np.asarray(voltage, dtype=dtype))
        circuit.attrs["voltage_rms_v"] = float(np.sqrt(np.mean(np.square(voltage))))
        f.create_dataset("events/kind", data=list(kinds), dtype=h5py.string_dtype())


class DigestTest(unittest.TestCase):
    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory()
        self.voltage = np.linspace(-1.0, 1.0, 101)

    def tearDown(self):
        self.scratch.cleanup()

    def lines(self, **kwargs):
        path = os.path.join(self.scratch.name, f"f{len(os.listdir(self.scratch.name))}.h5")
        write(path, **kwargs)
        return golden_digest.file_lines(path)

    def test_same_content_same_digest(self):
        self.assertEqual(self.lines(voltage=self.voltage), self.lines(voltage=self.voltage))

    def test_one_ulp_in_one_sample_is_seen_and_sized(self):
        changed = self.voltage.copy()
        changed[50] = np.nextafter(changed[50], 1.0)
        before, after = self.lines(voltage=self.voltage), self.lines(voltage=changed)
        differences = golden_digest.compare({"case": before}, {"case": after})
        # The dataset changes; the rms attribute may or may not move by that ulp.
        self.assertTrue(any(d.startswith("[case] /circuit/voltage: values changed") for d in differences),
                        differences)

    def test_provenance_and_wall_times_are_not_results(self):
        base = self.lines(voltage=self.voltage, attributes={"run_wall_time_s": 1.5, "threads": 2})
        other = self.lines(voltage=self.voltage, attributes={"run_wall_time_s": 9.25, "threads": 8})
        self.assertEqual(base, other)

    def test_numeric_attribute_is_a_result(self):
        base = self.lines(voltage=self.voltage, attributes={"valid": 1})
        other = self.lines(voltage=self.voltage, attributes={"valid": 0})
        self.assertEqual(golden_digest.compare({"c": base}, {"c": other}),
                         ["[c] /@valid: was: <i8 1\n        now: <i8 0"])

    def test_text_dataset_is_a_result(self):
        self.assertNotEqual(self.lines(voltage=self.voltage, kinds=("stick", "slip")),
                            self.lines(voltage=self.voltage, kinds=("stick", "reversal")))

    def test_byte_order_of_storage_does_not_matter(self):
        # The same values stored big-endian are the same result.
        self.assertEqual(self.lines(voltage=self.voltage, dtype="<f8"),
                         self.lines(voltage=self.voltage, dtype=">f8"))

    def test_a_narrower_type_is_a_change(self):
        self.assertNotEqual(self.lines(voltage=self.voltage, dtype="<f8"),
                            self.lines(voltage=self.voltage, dtype="<f4"))

    def test_missing_and_new_cases_and_objects_are_reported(self):
        base = self.lines(voltage=self.voltage)
        fewer = [line for line in base if not line.startswith("/events/kind")]
        report = golden_digest.compare({"a": base, "gone": base}, {"a": fewer, "new": base})
        self.assertIn("[a] /events/kind: gone from the output", report)
        self.assertIn("[gone] in the digest file but no longer a case", report)
        self.assertIn("[new] a new case with no digest", report)

    def full_lines(self, **kwargs):
        path = os.path.join(self.scratch.name, f"f{len(os.listdir(self.scratch.name))}.h5")
        write(path, **kwargs)
        return golden_digest.file_lines(path, include_text=True)

    def test_same_sees_text_attributes_but_not_creation_times(self):
        # `same` (distributed and sharded runs against one run) compares the provenance too:
        # another title is a difference, another creation time is not (EXCLUDED_ATTRIBUTES).
        base = self.full_lines(voltage=self.voltage, attributes={"created_utc": "2026-01-01T00:00:00Z"})
        later = self.full_lines(voltage=self.voltage, attributes={"created_utc": "2027-05-05T10:00:00Z"})
        retitled = self.full_lines(voltage=self.voltage, attributes={"title": "another title"})
        self.assertEqual(base, later)
        self.assertEqual(golden_digest.compare({"c": base}, {"c": retitled})[0].split(":")[0], "[c] /@title")

    def test_digest_file_round_trip(self):
        path = os.path.join(self.scratch.name, "digests.txt")
        digests = {"b": self.lines(voltage=self.voltage), "a": ["/x <f8 1 0123456789abcdef l2=1.0"]}
        golden_digest.write_digests(digests, path, "/bin/true")  # any program: only its --version is read
        read, header = golden_digest.read_digests(path)
        self.assertEqual(read, digests)
        self.assertTrue(any("Regenerate" in h for h in header))


if __name__ == "__main__":
    unittest.main()
