"""Bad input gives clear messages (exceptions headless), never a half-written document."""
import json
from unittest import mock

import FreeCAD
import Mesh
import Part

import lighting
from lighting.export import tessellate as tessellate_mod
from lighting.objects import results as results_obj
from lighting.solver import machine, run
from wbtest import DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector


def _texts(report, level):
    return [m.text for m in report.messages if m.level == level]


class BadInput(DocTestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("Bad")
        self.box = self.doc.addObject("Part::Box", "Room")  # the floor slab of a "room"
        self.box.Length, self.box.Width, self.box.Height = 4000, 4000, 100
        self.doc.recompute()
        self.analysis = lighting.make_analysis(self.doc)

    def test_no_luminaires_no_targets(self):
        with self.assertRaises(lighting.CheckError) as ctx:
            lighting.analyze(self.doc, output_dir=work_dir("bad"))
        text = str(ctx.exception)
        print(f"\nmessage: {text}")
        self.assertIn("No luminaires", text)
        self.assertIn("No targets", text)
        self.assertEqual(self.analysis.Status, "check failed")
        self.assertIsNone(results_obj.of_analysis(self.analysis))

    def test_luminaire_inside_wall(self):
        wall = self.doc.addObject("Part::Box", "Wall")
        wall.Length, wall.Width, wall.Height = 200, 4000, 3000
        wall.Placement.Base = V(5000, 0, 0)
        self.doc.recompute()
        lighting.make_luminaire(self.doc, (5.1, 2.0, 1.5), kind="Point", name="Buried")
        lighting.make_grid_target(self.doc, self.box, wall_band_m=0.5)
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        errors = _texts(report, "error")
        self.assertTrue(any("Buried" in e and "inside 'Wall'" in e for e in errors), errors)

    def test_luminaire_flush_with_ceiling_warns(self):
        ceiling = self.doc.addObject("Part::Box", "Ceiling")
        ceiling.Length, ceiling.Width, ceiling.Height = 4000, 4000, 200
        ceiling.Placement.Base = V(0, 0, 3000)
        self.doc.recompute()
        lighting.make_luminaire(self.doc, (2.0, 2.0, 3.0), name="Flush")
        lighting.make_luminaire(self.doc, (1.0, 1.0, 2.99), name="Below")
        lighting.make_grid_target(self.doc, self.box)
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        warnings = _texts(report, "warning")
        self.assertTrue(any("'Flush' lies on 'Ceiling'" in w for w in warnings), warnings)
        self.assertFalse(any("'Below'" in w for w in warnings), warnings)
        self.assertTrue(report.ok)

    def test_open_shell_and_open_mesh_warn(self):
        faces = Part.makeBox(1000, 1000, 1000).Faces[:5]  # one side missing
        leaky = self.doc.addObject("Part::Feature", "Leaky")
        leaky.Shape = Part.Shell(faces)
        cup = self.doc.addObject("Mesh::Feature", "Cup")
        box_mesh = Mesh.createBox(500, 500, 500)
        box_mesh.removeFacets([0, 1])
        cup.Mesh = box_mesh
        lighting.make_luminaire(self.doc, (2.0, 2.0, 2.5), kind="Point")
        lighting.make_grid_target(self.doc, self.box)
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        warnings = _texts(report, "warning")
        self.assertTrue(any("'Leaky'" in w and "open shell" in w for w in warnings), warnings)
        self.assertTrue(any("'Cup'" in w and "not closed" in w for w in warnings), warnings)
        self.assertTrue(report.ok)  # warnings do not block

    def test_absurd_values(self):
        lighting.make_luminaire(self.doc, (2.0, 2.0, 2.5), maintenance_factor=1.5)
        lighting.make_grid_target(self.doc, self.box, wall_band_m=3.0)  # band eats the room
        self.analysis.Photons = 0
        self.analysis.Confidence = 1.5
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        errors = "\n".join(_texts(report, "error"))
        for fragment in ("maintenance factor must be in (0, 1]", "wall band",
                         "Photons must be >= 1", "Confidence must be in (0, 1)"):
            self.assertIn(fragment, errors)

    @needs_solver
    def test_scene_values_come_from_the_solver_check(self):
        """One validator: a value the scene carries is judged by lightsolver.check_scene_json
        and reported against its object with the scene field; 0 lm is a switched-off
        luminaire, and only a scene where every luminaire is off warns."""
        bad = lighting.make_luminaire(self.doc, (2.0, 2.0, 2.5), kind="Spot", name="Spot")
        bad.BeamAngle, bad.FieldAngle = 60, 30
        lighting.make_grid_target(self.doc, self.box)
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        errors = [m for m in report.errors]
        self.assertEqual(len(errors), 1, report.format())
        self.assertEqual(errors[0].object_name, bad.Name)
        self.assertIn("luminaires[0].beam_angle_deg", errors[0].text)
        self.assertIn("'Spot'", errors[0].text)
        bad.BeamAngle, bad.FieldAngle = 30, 60
        bad.FluxLumen = -5.0
        report = lighting.check(self.doc, need_solver=False)
        self.assertIn("luminaires[0].flux_lm: must be a finite value >= 0",
                      "\n".join(_texts(report, "error")))
        bad.FluxLumen = 0.0
        report = lighting.check(self.doc, need_solver=False)
        self.assertTrue(report.ok, report.format())
        self.assertTrue(any("all luminaires have zero flux" in w
                            for w in _texts(report, "warning")), report.format())
        lighting.make_luminaire(self.doc, (1.0, 1.0, 2.5), kind="Point", name="On")
        self.doc.recompute()
        report = lighting.check(self.doc, need_solver=False)
        self.assertTrue(report.ok, report.format())
        self.assertFalse(any("zero flux" in w for w in _texts(report, "warning")))

    def test_shape_that_fails_to_tessellate(self):
        lighting.make_luminaire(self.doc, (2.0, 2.0, 2.5), kind="Point")
        lighting.make_grid_target(self.doc, self.box)
        broken = self.doc.addObject("Part::Box", "Broken")
        broken.Placement.Base = V(1000, 1000, 0)
        self.doc.recompute()
        real = tessellate_mod.tessellate_faces

        def failing(shape, linear, angular):
            if abs(shape.BoundBox.XMin - 1000.0) < 1e-6:
                raise RuntimeError("BRepMesh failed")  # what a broken B-rep does
            return real(shape, linear, angular)

        def face_failures(shape, linear, angular):
            if abs(shape.BoundBox.XMin - 1000.0) < 1e-6:
                return [None] * len(shape.Faces), ["Face1 could not be tessellated"]
            return real(shape, linear, angular)
        from lighting.export import scene as scene_mod

        # Whole-shape and face-level failures: reported, the object left out, export goes on.
        for side_effect in (failing, face_failures):
            with mock.patch.object(scene_mod, "tessellate_faces", side_effect=side_effect):
                result = scene_mod.build_scene(self.analysis)
            warnings = _texts(result.report, "warning")
            self.assertTrue(any("'Broken' failed to tessellate" in w and "left out" in w
                                for w in warnings), warnings)
            self.assertNotIn("Broken", result.object_meshes)
            self.assertIn("Room", result.object_meshes)
            self.assertTrue(result.report.ok)

    def test_missing_solver_is_a_clear_error(self):
        lighting.make_luminaire(self.doc, (2.0, 2.0, 2.5), kind="Point")
        lighting.make_grid_target(self.doc, self.box)
        self.doc.recompute()
        with mock.patch.object(run, "load_module",
                               side_effect=run.SolverUnavailableError("lightsolver missing (test)")):
            with self.assertRaises(lighting.CheckError) as ctx:
                lighting.analyze(self.doc, output_dir=work_dir("nosolver"))
        self.assertIn("lightsolver missing (test)", str(ctx.exception))

    @needs_solver
    def test_solver_failure_keeps_document(self):
        doc = build_office(photons=20000)
        analysis = doc.getObject("LightingAnalysis")
        job = machine.AnalysisRun(analysis, output_dir=work_dir("solverfail"))
        job.check()
        path = job.prepare()
        with open(path, encoding="utf-8") as stream:
            scene = json.load(stream)
        scene["luminaires"][0]["flux_lm"] = -5  # the solver validates every field
        with open(path, "w", encoding="utf-8") as stream:
            json.dump(scene, stream)
        with self.assertRaises(lighting.SolverError) as ctx:
            job.solve()
        message = job.fail(ctx.exception)
        print(f"\nsolver message: {message}")
        self.assertIn("flux_lm", message)
        self.assertTrue(analysis.Status.startswith("failed:"))
        self.assertIsNone(results_obj.of_analysis(analysis))
