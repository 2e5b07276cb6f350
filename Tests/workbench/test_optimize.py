"""Inverse design from the document: placement domains become position variables on their
candidate lattice, the optimizer's best places the luminaire over the target, apply() moves the
template and makes (then reuses) copies."""
import FreeCAD

import lighting
from lighting.objects import placement_domain as domain_mod
from lighting.solver import optimize
from wbtest import DocTestCase, load_scene, needs_solver, work_dir

V = FreeCAD.Vector


def build_room(max_luminaires: int = 1):
    """A 4 x 4 m floor and ceiling slab (3 m up), a desk in one corner whose top is the target,
    a point light and a placement domain on the ceiling's underside: candidates 1 m apart,
    0.5 m from the edges, i.e. x, y in {1, 2, 3} m, 5 cm below the ceiling."""
    doc = FreeCAD.newDocument("OptimizeRoom")
    floor = doc.addObject("Part::Box", "Floor")
    floor.Length, floor.Width, floor.Height = 4000, 4000, 100
    floor.Placement.Base = V(0, 0, -100)
    ceiling = doc.addObject("Part::Box", "Ceiling")
    ceiling.Length, ceiling.Width, ceiling.Height = 4000, 4000, 100
    ceiling.Placement.Base = V(0, 0, 3000)
    desk = doc.addObject("Part::Box", "Desk")
    desk.Length, desk.Width, desk.Height = 600, 600, 750
    desk.Placement.Base = V(3000, 3000, 0)
    doc.recompute()
    analysis = lighting.make_analysis(doc, photons=20000, seed=3)
    lum = lighting.make_luminaire(doc, position_m=(1.0, 1.0, 2.9), kind="Point", flux_lm=2000,
                                  analysis=analysis)
    target = lighting.make_face_target(doc, [(desk, "Face6")], analysis=analysis)
    domain = lighting.make_placement_domain(doc, ceiling, "Face5", resolution_m=1.0,
                                            max_luminaires=max_luminaires, offset_m=0.05,
                                            edge_margin_m=0.5, template=lum, analysis=analysis)
    domain.MinLuminaires = max_luminaires
    doc.recompute()
    return doc, analysis, lum, target, domain


def near(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


class Optimize(DocTestCase):
    def test_domain_rectangle_cells_are_the_candidates(self):
        doc, _, _, _, domain = build_room()
        rect = domain_mod.optimization_rectangle(domain)
        self.assertEqual(rect["cells"], [5, 5])
        points, _ = domain_mod.candidates(domain)
        self.assertEqual(len(points), 9)
        # Cell centres corner + (i + 0.5)/5 edge1 + (j + 0.5)/5 edge2 hit every candidate.
        c, e1, e2 = (V(*rect[k]) for k in ("corner", "edge1", "edge2"))
        centres = [c + e1 * ((i + 0.5) / 5) + e2 * ((j + 0.5) / 5)
                   for i in range(5) for j in range(5)]
        for p in points:
            self.assertTrue(any((q * 1000.0 - p).Length < 1e-3 for q in centres), p)
        outer = rect["within"]["outer"]
        xs, ys = [q[0] for q in outer], [q[1] for q in outer]
        self.assertAlmostEqual(min(xs), 0.5, 6)  # the face shrunk by EdgeMargin
        self.assertAlmostEqual(max(ys), 3.5, 6)
        self.assertTrue(all(abs(q[2] - 2.95) < 1e-9 for q in outer))
        self.assertEqual(rect["within"]["holes"], [])

    @needs_solver
    def test_best_place_is_over_the_desk_and_apply_moves_the_luminaire(self):
        doc, analysis, lum, target, _ = build_room()
        result = lighting.optimize_placement(
            doc, target, goal="maximize_mean_illuminance", iterations=30, seed=2,
            screening_photons=20000, confirmation_photons=100000,
            output_dir=work_dir("optimize"))
        members = result.members
        self.assertGreater(len(members), 0)
        for m in members:
            x, y, z = m["positions_m"][lum.Name]
            self.assertIn(round(x, 6), (1.0, 2.0, 3.0))
            self.assertIn(round(y, 6), (1.0, 2.0, 3.0))
            self.assertAlmostEqual(z, 2.95, 6)
        self.assertTrue(near(members[0]["positions_m"][lum.Name], (3.0, 3.0, 2.95)))
        lo, hi = members[0]["ci"]
        self.assertLessEqual(lo, members[0]["mean"])
        self.assertLessEqual(members[0]["mean"], hi)
        placed = result.apply()
        self.assertEqual([o.Name for o in placed], [lum.Name])
        self.assertTrue(near(lum.Placement.Base, (3000.0, 3000.0, 2950.0), 1e-6))

    @needs_solver
    def test_two_luminaires_make_one_copy_reused_next_time(self):
        doc, analysis, lum, target, _ = build_room(max_luminaires=2)
        kwargs = dict(goal="maximize_mean_illuminance", iterations=30, seed=4,
                      screening_photons=20000, confirmation_photons=100000)
        first = lighting.optimize_placement(doc, target, output_dir=work_dir("opt2"), **kwargs)
        self.assertEqual(len(first.placements), 2)
        before = len(doc.Objects)
        placed = first.apply()
        self.assertEqual(len(doc.Objects), before + 1)  # one copy made
        copy = placed[1]
        self.assertEqual(copy.Label, f"{lum.Label}_copy1")
        self.assertIn(copy, analysis.Group)
        self.assertEqual(copy.LuminaireType, "Point")
        # Both want the cell over the desk, but never share one: one takes it, the other the
        # nearest free candidate (1 m away).
        a, b = (o.Placement.Base for o in placed)
        self.assertAlmostEqual((a - b).Length, 1000.0, 6)
        self.assertTrue(any(near(p, (3000.0, 3000.0, 2950.0), 1e-6) for p in (a, b)))
        # The copy is now a luminaire of the analysis: the next run moves it, adds none.
        second = lighting.optimize_placement(doc, target, output_dir=work_dir("opt3"), **kwargs)
        self.assertEqual([p.obj for p in second.placements], [lum, copy])
        second.apply()
        self.assertEqual(len(doc.Objects), before + 1)

    def test_eta_is_measured_time_per_trace_times_traces_left(self):
        stats = {"evaluations": 10, "elapsed_seconds": 5.0, "iteration": 0}
        self.assertAlmostEqual(optimize.eta_seconds(stats, 200, 40), 15.0)  # 30 traces x 0.5 s
        self.assertIsNone(optimize.eta_seconds(stats, 200, 0))  # no iteration done: unknown
        stats["iteration"] = 2  # 5 traces per iteration: the iteration budget ends later
        self.assertAlmostEqual(optimize.eta_seconds(stats, 200, 40), 15.0)
        self.assertAlmostEqual(optimize.eta_seconds(stats, 4, 0), 5.0)  # 2 x 5 x 0.5 s
        self.assertIsNone(optimize.eta_seconds({"evaluations": 1, "elapsed_seconds": 0.2}, 9))
        text = optimize.format_progress(dict(stats, best=(600.0, 550.0, 650.0), isoc_size=3),
                                        200, 40)
        self.assertIn("10 of 40 evaluations", text)
        self.assertIn("about 15 s left", text)

    def test_default_intention_follows_the_target_requirements(self):
        doc, *_ = build_room()
        grid = lighting.make_grid_target(doc, doc.getObject("Floor"), "Face6", required_lux=500.0,
                                         required_uniformity=0.6)
        self.assertEqual(optimize.default_intention(grid),
                         ("minimize_installed_flux", 500.0, 0.6))
        grid.RequiredLux = 0.0
        self.assertEqual(optimize.default_intention(grid)[0], "maximize_mean_illuminance")


    def test_bad_requests_name_the_problem(self):
        doc, analysis, lum, target, domain = build_room()
        with self.assertRaises(ValueError):
            lighting.optimize_placement(doc, target, goal="maximize_joy",
                                        output_dir=work_dir("bad"))
        with self.assertRaises(ValueError):  # uniformity needs a required mean
            lighting.optimize_placement(doc, target, goal="maximize_uniformity",
                                        output_dir=work_dir("bad"))
        twin = lighting.make_placement_domain(doc, doc.getObject("Floor"), "Face6", template=lum,
                                              analysis=analysis)
        doc.recompute()
        with self.assertRaises(lighting.CheckError) as ctx:
            lighting.optimize_placement(doc, target, goal="maximize_mean_illuminance",
                                        output_dir=work_dir("bad"))
        self.assertIn("both place", str(ctx.exception.report.format()))
        doc.removeObject(twin.Name)
        other = lighting.make_analysis(doc, name="OtherAnalysis")
        domain.Template = lighting.make_luminaire(doc, kind="Point", analysis=other)
        with self.assertRaises(lighting.CheckError) as ctx:  # not exported by this analysis
            lighting.optimize_placement(doc, target, goal="maximize_mean_illuminance",
                                        analysis=analysis, output_dir=work_dir("bad"))
        self.assertIn("is not a luminaire of the analysis", str(ctx.exception.report.format()))
        domain.Template = None
        with self.assertRaises(lighting.CheckError) as ctx:
            lighting.optimize_placement(doc, target, goal="maximize_mean_illuminance",
                                        output_dir=work_dir("bad"))
        self.assertIn("no Template", str(ctx.exception.report.format()))


def luminaire_positions(analysis):
    """{label: global position (mm)} of the analysis' luminaires."""
    from lighting.objects import analysis as analysis_mod

    return {o.Label: o.getGlobalPlacement().Base for o in analysis_mod.luminaires(analysis)}


def smallest_gap_mm(points):
    pts = list(points)
    return min(((a - b).Length for i, a in enumerate(pts) for b in pts[i + 1:]),
               default=float("inf"))


class OfficeOptimize(DocTestCase):
    """The office example as a designer meets it: four hand-placed panels, a workplane that
    requires Em 500 lx and U0 0.6, a ceiling domain for up to six panels."""

    KW = dict(iterations=200, evaluations=60, seed=1, screening_photons=100000,
              confirmation_photons=1000000)

    def setUp(self):
        from wbtest import build_office
        import office_model

        self.doc = build_office(photons=20000)
        self.doc.UndoMode = 1
        names = office_model.OBJECTS
        self.analysis = self.doc.getObject(names["analysis"])
        self.workplane = self.doc.getObject(names["workplane"])
        self.before = luminaire_positions(self.analysis)

    @needs_solver
    def test_replacing_leaves_exactly_the_optimum_and_undo_restores(self):
        others = optimize.others_on_domains(self.analysis)
        self.assertEqual(sorted(o.Label for o in others),
                         ["Luminaire02", "Luminaire03", "Luminaire04"])
        progress = []
        result = lighting.optimize_placement(
            self.doc, self.workplane, output_dir=work_dir("office-replace"),
            replace_others=True, progress=progress.append, **self.KW)
        # The default intention for a target with requirements: least flux meeting them.
        scene = load_scene(result.scene_file)
        self.assertEqual(scene["optimization"]["intention"],
                         {"type": "minimize_installed_flux", "target": self.workplane.Name,
                          "min_mean_lux": 500.0, "min_uniformity": 0.6})
        names = {lum["name"] for lum in scene["luminaires"]}
        self.assertFalse(names & {o.Name for o in others})  # left out of the search
        # Each placed luminaire is its own group, so a step re-traces only the one it moves and
        # switching an optional one on or off traces nothing.
        placed_names = {p.name for p in result.placements}
        for lum in scene["luminaires"]:
            if lum["name"] in placed_names:
                self.assertEqual(lum["group"], lum["name"])
        counters = result.raw["counters"]
        self.assertLess(counters["photons_traced"], counters["photons"])
        # Progress came per trace, long before the first iteration ended, with a time estimate.
        first = progress[0]
        self.assertEqual(first["event"], "evaluation")
        self.assertEqual(first["iteration"], 0)
        self.assertTrue(any(p["eta_s"] is not None and p["iteration"] == 0 for p in progress))
        members = result.members
        self.assertGreater(len(members), 0, result.raw["counters"])
        best = members[0]
        em, u0 = best["constraints"]
        self.assertGreaterEqual(em, 500.0)
        self.assertGreaterEqual(u0, 0.6)
        self.assertEqual(best["mean"], best["count"] * 5200.0 * 0.8)  # maintained flux
        for m in members:
            self.assertGreaterEqual(smallest_gap_mm(
                FreeCAD.Vector(*p) * 1000.0 for p in m["positions_m"].values()), 599.0)
        undo_steps = self.doc.UndoCount
        placed = result.apply()
        self.assertEqual(self.doc.UndoCount, undo_steps + 1)  # one undo step
        after = luminaire_positions(self.analysis)
        self.assertEqual(len(after), best["count"])
        self.assertEqual(len(placed), best["count"])
        self.assertEqual(sorted(after), sorted(o.Label for o in placed))
        self.assertGreaterEqual(smallest_gap_mm(after.values()), 599.0)
        for label in ("Luminaire02", "Luminaire03", "Luminaire04"):
            self.assertIsNone(self.doc.getObjectsByLabel(label) or None)
        self.doc.undo()
        self.doc.recompute()
        restored = luminaire_positions(self.analysis)
        self.assertEqual(sorted(restored), sorted(self.before))
        for label, p in self.before.items():
            self.assertLess((restored[label] - p).Length, 1e-6, label)

    @needs_solver
    def test_keeping_others_touches_none_of_them(self):
        result = lighting.optimize_placement(
            self.doc, self.workplane, output_dir=work_dir("office-keep"), **self.KW)
        self.assertEqual(result.removed, [])
        members = result.members
        self.assertGreater(len(members), 0, result.raw["counters"])
        placed = result.apply()
        after = luminaire_positions(self.analysis)
        for label in ("Luminaire02", "Luminaire03", "Luminaire04"):
            self.assertLess((after[label] - self.before[label]).Length, 1e-9, label)
        own = [label for label in after if label not in ("Luminaire02", "Luminaire03",
                                                         "Luminaire04")]
        self.assertEqual(sorted(own), sorted(o.Label for o in placed))
        self.assertEqual(len(own), members[0]["count"])
        self.assertGreaterEqual(smallest_gap_mm(after.values()), 599.0)  # none on the others


class AppliedCopyLabels(DocTestCase):
    def test_installed_copies_are_numbered_in_order(self):
        """The optimum installs candidates 1, 3 and 4: after apply() they read _copy1, _copy2,
        _copy3 (issue 25: not "copy1, copy3, copy4"); the template keeps its label."""
        doc = FreeCAD.newDocument("CopyLabels")
        template = lighting.make_luminaire(doc, (1.0, 1.0, 2.9), name="Lum")
        placed = [optimize.Placement(template.Name, template, None, template, template.Label)]
        for k in (1, 3, 4):
            copy = doc.copyObject(template)
            copy.Label = f"{template.Label}{optimize.COPY_SUFFIX}{k}"
            placed.append(optimize.Placement(copy.Name, template, None, copy, copy.Label))
        placed.append(optimize.Placement("gone", template, None, None, "left out"))
        optimize._renumber_copies(placed)
        self.assertEqual([p.obj.Label for p in placed[:4]],
                         [template.Label] + [f"{template.Label}_copy{k}" for k in (1, 2, 3)])
        FreeCAD.closeDocument(doc.Name)
