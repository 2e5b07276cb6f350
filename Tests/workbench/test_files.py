"""Files the workbench writes are never lost: atomic writes (temporary file in the same folder,
fsync, rename) that leave the previous file intact on failure and no temporary file behind,
and output folders checked before the solver starts.

The suites run as root, where permission bits do not stop a write, so unwritable places are
made otherwise: a missing folder, a folder as the target, a regular file used as a folder,
/proc (no new file can be created there, even by root), and an fsync that fails."""
import json
import os
import unittest
from unittest import mock

import lighting
from lighting import files
from lighting.export import ply
from lighting.messages import ExportError, SolverError
from lighting.solver import machine
from wbtest import DocTestCase, build_office, work_dir


class AtomicWrites(unittest.TestCase):
    def setUp(self):
        self.folder = work_dir("files")

    def path(self, name):
        return os.path.join(self.folder, name)

    def read(self, name):
        with open(self.path(name), encoding="utf-8") as stream:
            return stream.read()

    def test_write_replaces_and_leaves_no_temporary_file(self):
        files.write_text(self.path("r.json"), "first")
        files.write_text(self.path("r.json"), "second é")
        self.assertEqual(self.read("r.json"), "second é")
        files.write_bytes(self.path("b.bin"), b"\x00\x01")
        self.assertEqual(sorted(os.listdir(self.folder)), ["b.bin", "r.json"])

    def test_a_failed_write_keeps_the_previous_file(self):
        files.write_text(self.path("r.json"), "previous results")
        # The data reached the temporary file, then fsync failed (a full or broken disk).
        with mock.patch("os.fsync", side_effect=OSError(5, "Input/output error")):
            with self.assertRaises(OSError):
                files.write_text(self.path("r.json"), "new results")
            with self.assertRaises(OSError):
                ply.write_ply(self.path("r.json"), [(0, 0, 0)] * 3, [(0, 1, 2)])
        self.assertEqual(self.read("r.json"), "previous results")
        self.assertEqual(os.listdir(self.folder), ["r.json"])

    def test_permissions_are_kept_and_links_followed(self):
        files.write_text(self.path("real.json"), "old")
        os.chmod(self.path("real.json"), 0o640)
        os.symlink(self.path("real.json"), self.path("link.json"))
        files.write_text(self.path("link.json"), "new")
        self.assertTrue(os.path.islink(self.path("link.json")))
        self.assertEqual(self.read("real.json"), "new")
        self.assertEqual(os.stat(self.path("real.json")).st_mode & 0o777, 0o640)

    def test_unwritable_paths_are_named(self):
        os.mkdir(self.path("folder"))
        files.write_text(self.path("plain"), "keep")
        cases = {self.path("missing/r.json"): "does not exist",
                 self.path("folder"): "it is a folder",
                 self.path("plain/r.json"): "is not a folder",
                 "/proc/version": "cannot create files in '/proc'",
                 "/dev/null": "not a regular file"}
        with open("/proc/version", encoding="utf-8") as stream:
            version = stream.read()
        for path, why in cases.items():
            with self.assertRaises(OSError) as err:
                files.check_writable(path, "results file")
            self.assertIn(f"cannot write the results file '{path}'", str(err.exception))
            self.assertIn(why, str(err.exception))
            with self.assertRaises(OSError) as err:
                files.write_text(path, "x")
            self.assertIn(path, str(err.exception))
        with open("/proc/version", encoding="utf-8") as stream:
            self.assertEqual(stream.read(), version)
        self.assertEqual(sorted(os.listdir(self.folder)), ["folder", "plain"])
        self.assertEqual(self.read("plain"), "keep")
        files.check_writable(self.path("new.json"))  # fine, and leaves nothing
        self.assertEqual(sorted(os.listdir(self.folder)), ["folder", "plain"])

    def test_copy_file(self):
        files.write_bytes(self.path("a.ies"), b"IESNA")
        files.copy_file(self.path("a.ies"), self.path("b.ies"))
        self.assertEqual(self.read("b.ies"), "IESNA")


class OutputChecks(DocTestCase):
    def test_an_unwritable_output_folder_stops_the_export(self):
        doc = build_office(photons=10 ** 9)
        calls = []
        with self.assertRaises(ExportError) as err:
            lighting.analyze(doc, output_dir="/proc/lighting-test",
                             progress=lambda done, total: calls.append(done))
        self.assertIn("/proc/lighting-test", str(err.exception))
        self.assertEqual(calls, [])

    def test_the_results_file_is_checked_before_tracing(self):
        doc = build_office(photons=10 ** 9)
        folder = work_dir("results-check")
        job = machine.AnalysisRun(doc.getObject("LightingAnalysis"), output_dir=folder)
        job.check(need_solver=False)
        job.prepare()
        os.mkdir(os.path.join(folder, "results.json"))  # something in the way
        calls = []
        with self.assertRaises(SolverError) as err:
            job.solve(lambda done, total: calls.append(done))
        self.assertIn("results.json", str(err.exception))
        self.assertIn("it is a folder", str(err.exception))
        self.assertEqual(calls, [])  # nothing traced
        with open(job.scene_file, encoding="utf-8") as stream:
            self.assertEqual(json.load(stream)["format"], "lightsolver.scene/1")
        self.assertEqual(sorted(os.listdir(folder)), ["results.json", "scene.json"])


if __name__ == "__main__":
    unittest.main()
