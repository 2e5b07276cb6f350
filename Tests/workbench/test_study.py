"""What accuracy costs, from the workbench: lighting.accuracy_study runs ``lightsolver study``
on the analysis' exported scene (one run, doubling checkpoints) and keeps its plot."""
import os
import unittest

import lighting
from wbtest import DocTestCase, build_office, needs_solver, work_dir


class AccuracyStudy(DocTestCase):
    @needs_solver
    def test_office_study_rows_goals_and_plot(self):
        doc = build_office()
        study = lighting.accuracy_study(doc, max_photons=80_000, output_dir=work_dir("study"))
        rows = study.data["rows"]
        self.assertEqual([r["photons"] for r in rows], [10_000, 20_000, 40_000, 80_000])
        # Monte Carlo: the worst cell's width shrinks as photons double (about 1/sqrt(2)).
        widths = [r["all"]["worst_relative_half_width"] for r in rows]
        self.assertTrue(all(b < a for a, b in zip(widths, widths[1:])), widths)
        self.assertEqual([g["accuracy"] for g in study.goals], [0.1, 0.05, 0.02, 0.01, 0.005])
        photons = [g["photons"] for g in study.goals]
        self.assertTrue(all(b > a for a, b in zip(photons, photons[1:])), photons)
        self.assertIn("\u00b11 % per cell", study.goals_text())
        with open(study.plot_file, "rb") as stream:
            self.assertEqual(stream.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertGreater(os.path.getsize(study.plot_file), 5000)

    def test_without_the_program_the_error_says_what_to_do(self):
        from lighting.messages import SolverError
        from lighting.solver import run, study

        saved = run.cli_executable
        run.cli_executable = lambda: None
        try:
            with self.assertRaisesRegex(SolverError, "needs the lightsolver program"):
                study.study_scene("/nowhere/scene.json")
        finally:
            run.cli_executable = saved


if __name__ == "__main__":
    unittest.main()
