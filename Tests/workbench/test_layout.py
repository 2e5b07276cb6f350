"""Luminaire layouts (rows x columns over a ceiling face), default luminaire placement and the
coincident-luminaire warning (issue 12, item 5)."""
import os

import FreeCAD

import lighting
from lighting import placement
from lighting.objects import luminaire_layout as layout_mod
from lighting.objects.base import proxy_type
from lighting.solver import check as check_mod
from wbtest import REPO, DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector
PHOTOMETRIC_FILE = "batwing_panel.ldt"


def _office_without_luminaires():
    """The example office with its four luminaires and its placement domain removed."""
    import office_model

    doc = build_office(photons=50000, seed=3)
    for name in ("CeilingDomain", "Luminaire01", "Luminaire02", "Luminaire03", "Luminaire04"):
        doc.removeObject(name)
    doc.recompute()
    ceiling = doc.getObject(office_model.OBJECTS["ceiling"])
    face = office_model.find_face(ceiling.Shape, V(0, 0, -1), V(0, 0, 3000))
    return doc, ceiling, face


def _centres(scene):
    """Scene luminaire name -> centre (m, rounded to 0.1 mm) of its area emitter."""
    out = {}
    for lum in scene["luminaires"]:
        corner, e1, e2 = lum["corner"], lum["edge1"], lum["edge2"]
        out[lum["name"]] = tuple(round(corner[i] + 0.5 * (e1[i] + e2[i]), 4) for i in range(3))
    return out


def _layout(doc, ceiling, face, **kw):
    args = dict(rows=2, columns=3, kind="Area", flux_lm=4000.0, maintenance_factor=0.8,
                analysis=doc.getObject("LightingAnalysis"))
    args.update(kw)
    layout = lighting.add_luminaire_layout(doc, ceiling, face, **args)
    doc.recompute()
    return layout


class LayoutExport(DocTestCase):
    def setUp(self):
        self.doc, self.ceiling, self.face = _office_without_luminaires()

    def scene(self):
        from lighting.export.scene import build_scene

        result = build_scene(self.doc.getObject("LightingAnalysis"))
        self.assertTrue(result.report.ok, [m.text for m in result.report.errors])
        return result.scene

    def test_3x2_margins_exact(self):
        """Margins 1 m from the walls (not from the slab's edge over them): columns at 1.0,
        2.5, 4.0 m, rows at 1.0, 3.0 m, 5 cm under the ceiling, all aimed down."""
        layout = _layout(self.doc, self.ceiling, self.face, margin_x_m=1.0, margin_y_m=1.0)
        self.assertEqual(layout.MemberCount, 6)
        scene = self.scene()
        centres = _centres(scene)
        expected = {f"{layout.Name}_r{r + 1}c{c + 1}": (x, y, 2.95)
                    for r, y in enumerate((1.0, 3.0)) for c, x in enumerate((1.0, 2.5, 4.0))}
        self.assertEqual(centres, expected)
        template = layout.Template
        self.assertNotIn(template.Name, centres, "the template is the type, not a luminaire")
        for lum in scene["luminaires"]:
            self.assertAlmostEqual(lum["flux_lm"], 4000.0 * 0.8)
            e1, e2 = lum["edge1"], lum["edge2"]
            normal_z = e1[0] * e2[1] - e1[1] * e2[0]
            self.assertLess(normal_z, 0.0, "emitters face down")
        labels = scene["metadata"]["labels"]
        self.assertEqual(labels[f"{layout.Name}_r2c3"], f"{layout.Label} r2c3")
        self.assertEqual(sorted(scene["metadata"]["luminaire_layouts"][layout.Name]),
                         sorted(expected))

    def test_spacing_centred_and_even_field(self):
        """Spacing alone centres the field; neither spacing nor margin gives an even field
        (margin = half the spacing)."""
        layout = _layout(self.doc, self.ceiling, self.face, spacing_x_m=1.4, spacing_y_m=2.4)
        xs = sorted({c[0] for c in _centres(self.scene()).values()})
        ys = sorted({c[1] for c in _centres(self.scene()).values()})
        self.assertEqual((xs, ys), ([1.1, 2.5, 3.9], [0.8, 3.2]))
        layout.SpacingX, layout.SpacingY = 0.0, 0.0
        self.doc.recompute()
        xs = sorted({c[0] for c in _centres(self.scene()).values()})
        ys = sorted({c[1] for c in _centres(self.scene()).values()})
        self.assertEqual((xs, ys), ([0.8333, 2.5, 4.1667], [1.0, 3.0]))

    def test_edit_rows_moves_members(self):
        layout = _layout(self.doc, self.ceiling, self.face, margin_x_m=1.0, margin_y_m=1.0)
        layout.Rows = 3
        self.doc.recompute()
        self.assertEqual(layout.MemberCount, 9)
        self.assertEqual(len(layout.Shape.childShapes()), 9, "one marker per member")
        ys = sorted({c[1] for c in _centres(self.scene()).values()})
        self.assertEqual(ys, [1.0, 2.0, 3.0])
        layout.LuminaireRotation = 90.0
        layout.Template.Width, layout.Template.Length = 1200.0, 300.0
        self.doc.recompute()
        lum = self.scene()["luminaires"][0]
        # Width (local X) turned by 90 degrees lies along global Y.
        self.assertAlmostEqual(abs(lum["edge2"][1]), 1.2, places=6)
        self.assertAlmostEqual(abs(lum["edge1"][0]), 0.3, places=6)

    def test_save_reopen(self):
        layout = _layout(self.doc, self.ceiling, self.face, margin_x_m=1.0, margin_y_m=1.0,
                         rotation_deg=15.0)
        before = _centres(self.scene())
        path = os.path.join(work_dir("layout"), "layout.FCStd")
        self.doc.saveAs(path)
        name = layout.Name
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        layout = self.doc.getObject(name)
        self.assertEqual(proxy_type(layout), layout_mod.TYPE)
        self.assertEqual((layout.Rows, layout.Columns), (2, 3))
        self.assertAlmostEqual(float(layout.LuminaireRotation), 15.0)
        self.assertEqual(_centres(self.scene()), before)

    def test_bad_counts_name_the_layout(self):
        layout = _layout(self.doc, self.ceiling, self.face)
        layout.Rows = 0
        report = lighting.check(self.doc, need_solver=False)
        errors = [m.text for m in report.errors]
        self.assertTrue(any(layout.Label in e and "Rows and Columns" in e for e in errors), errors)
        layout.Rows, layout.MarginX, layout.SpacingX = 2, 1000.0, 2500.0
        errors = [m.text for m in lighting.check(self.doc, need_solver=False).errors]
        self.assertTrue(any("SpacingX/MarginX" in e for e in errors), errors)

    def test_rectangle_without_face(self):
        analysis = self.doc.getObject("LightingAnalysis")
        layout = lighting.add_luminaire_layout(self.doc, rows=1, columns=2, area_m=(2.0, 1.0),
                                               analysis=analysis, offset_m=0.0)
        layout.Placement = FreeCAD.Placement(V(1000, 1000, 2900), FreeCAD.Rotation())
        self.doc.recompute()
        self.assertEqual(sorted(_centres(self.scene()).values()),
                         [(1.5, 1.5, 2.9), (2.5, 1.5, 2.9)])
        # The markers are where the members are (not moved by the Placement twice).
        box = layout.Shape.BoundBox
        self.assertAlmostEqual(box.XMin, 1200.0, places=3)
        self.assertAlmostEqual(box.XMax, 2800.0, places=3)
        self.assertAlmostEqual(box.ZMax, 2920.0, places=3)

    def test_photometric_members_turn_with_rotation(self):
        """Members of a photometric type share its file; LuminaireRotation turns their C0."""
        path = os.path.join(REPO, "Resources", "luminaires", PHOTOMETRIC_FILE)
        layout = _layout(self.doc, self.ceiling, self.face, kind="Photometric",
                         photometric_file=path, flux_lm=3000.0, rotation_deg=30.0)
        scene = self.scene()
        self.assertEqual(len(scene["luminaires"]), 6)
        for lum in scene["luminaires"]:
            self.assertEqual(lum["file"], os.path.abspath(path))
            self.assertAlmostEqual(lum["rotation_deg"], 30.0, places=6)
            self.assertEqual([round(c, 12) + 0.0 for c in lum["aim"]], [0.0, 0.0, -1.0])
        self.assertEqual(layout.MemberCount, 6)

    @needs_solver
    def test_run_matches_separate_luminaires(self):
        """Em of the layout = Em of six luminaire objects with the same data and positions in
        one control group (a layout is one group: same seed and photons, identical scenes but
        for names, identical results)."""
        analysis = self.doc.getObject("LightingAnalysis")
        layout = _layout(self.doc, self.ceiling, self.face, margin_x_m=1.0, margin_y_m=1.0)
        with_layout = lighting.analyze(self.doc, photons=50000, seed=5,
                                       output_dir=work_dir("layout-run"))
        placements = [p for _, _, p in layout_mod.layout_placements(layout)]
        template = layout.Template.Name
        group = layout.Name  # its members' control group (objects/luminaire.py control_group)
        self.doc.removeObject(layout.Name)
        self.doc.removeObject(template)
        for i, where in enumerate(placements):
            single = lighting.make_luminaire(self.doc, kind="Area", flux_lm=4000.0,
                                             maintenance_factor=0.8, name=f"Single{i}",
                                             analysis=analysis)
            single.Placement = where
            single.ControlGroup = group
        self.doc.recompute()
        separate = lighting.analyze(self.doc, photons=50000, seed=5,
                                    output_dir=work_dir("single-run"))
        for name in ("Workplane", "DeskTop_target", "NorthWall"):
            print(f"\n{name}: layout {with_layout[name].mean_lux:.3f} lx, "
                  f"separate {separate[name].mean_lux:.3f} lx")
            self.assertGreater(with_layout[name].mean_lux, 50.0)
            self.assertAlmostEqual(with_layout[name].mean_lux, separate[name].mean_lux, places=6)


class Placement(DocTestCase):
    def test_default_spot_is_room_centre_under_ceiling(self):
        doc, ceiling, face = _office_without_luminaires()
        position, aim, text = placement.default_spot(doc)
        self.assertEqual((round(position.x, 3), round(position.y, 3), round(position.z, 3)),
                         (2500.0, 2000.0, 2950.0))
        self.assertEqual((aim.x, aim.y, round(aim.z, 9)), (0.0, 0.0, -1.0))
        self.assertIn("ceiling", text)
        solids = placement.model_solids(doc)
        position, aim = placement.spot_on_face(ceiling.Shape.getElement(face), solids)
        self.assertAlmostEqual((position - V(2500, 2000, 2950)).Length, 0.0, places=6)
        # A floor face: the luminaire goes under the ceiling above it, aimed down.
        import office_model

        floor = doc.getObject(office_model.OBJECTS["floor"])
        floor_face = office_model.find_face(floor.Shape, V(0, 0, 1), V(0, 0, 0))
        position, aim = placement.spot_on_face(floor.Shape.getElement(floor_face), solids)
        self.assertAlmostEqual((position - V(2500, 2000, 2950)).Length, 0.0, places=6)
        self.assertAlmostEqual(aim.z, -1.0)

    def test_ceiling_link_names_the_slab_face(self):
        """What the layout command uses with nothing selected: the ceiling's underside."""
        doc, ceiling, face = _office_without_luminaires()
        self.assertEqual(placement.ceiling_link(doc), (ceiling, face))

    def test_empty_document(self):
        doc = FreeCAD.newDocument("Empty")
        position, _, text = placement.default_spot(doc)
        self.assertEqual(position, V(0, 0, 2500))
        self.assertIn("no geometry", text)


class Coincident(DocTestCase):
    def test_two_luminaires_at_one_point_warn_naming_both(self):
        doc, ceiling, face = _office_without_luminaires()
        analysis = doc.getObject("LightingAnalysis")
        a = lighting.make_luminaire(doc, (2.5, 2.0, 2.95), name="First", analysis=analysis)
        b = lighting.make_luminaire(doc, (2.5, 2.005, 2.95), name="Second", analysis=analysis)
        doc.recompute()
        warnings = [m.text for m in lighting.check(doc, need_solver=False).warnings]
        hits = [w for w in warnings if "same point" in w]
        self.assertEqual(len(hits), 1, warnings)
        self.assertIn("'First'", hits[0])
        self.assertIn("'Second'", hits[0])
        b.Placement.Base = V(2500, 2000 + check_mod.COINCIDENT_MM + 1.0, 2950)
        doc.recompute()
        warnings = [m.text for m in lighting.check(doc, need_solver=False).warnings]
        self.assertFalse([w for w in warnings if "same point" in w], warnings)
        # A luminaire on a layout member's spot.
        layout = _layout(doc, ceiling, face, margin_x_m=1.0, margin_y_m=1.0)
        a.Placement.Base = V(1000, 1000, 2950)
        doc.recompute()
        hits = [w for w in (m.text for m in lighting.check(doc, need_solver=False).warnings)
                if "same point" in w]
        self.assertEqual(hits, [f"Luminaires 'First' and '{layout.Label} r1c1' are at the same "
                                "point (0.0 mm apart): one of them is probably placed twice; "
                                "move or delete it"])


class LayoutTypeOnTheLayout(DocTestCase):
    def test_file_flux_and_mf_edited_on_the_layout_reach_the_template_and_survive_reopening(self):
        """Issue 25: the layout's file, flux and MF are editable on the layout itself; bad
        values are refused; saving and reopening keeps both sides and writes nothing."""
        doc = FreeCAD.newDocument("LayoutType")
        layout = lighting.add_luminaire_layout(doc, rows=1, columns=2, area_m=(4.0, 3.0),
                                               flux_lm=3000.0, maintenance_factor=0.8)
        doc.recompute()
        template = layout.Template
        self.assertEqual((layout.FluxLumen, layout.MaintenanceFactor), (3000.0, 0.8))
        path = os.path.join(REPO, "Resources", "luminaires", "downlight.ies")
        layout.PhotometricFile = path
        layout.FluxLumen = 1500.0
        layout.MaintenanceFactor = 1.5  # refused: MF is in (0, 1]
        self.assertEqual(template.PhotometricFile, path)
        self.assertEqual(template.LuminaireType, "Photometric")
        self.assertEqual(template.FluxLumen, 1500.0)
        self.assertEqual((template.MaintenanceFactor, layout.MaintenanceFactor), (0.8, 0.8))
        template.FluxLumen = 1200.0  # a change on the template shows after a recompute
        doc.recompute()
        self.assertEqual(layout.FluxLumen, 1200.0)
        members = layout_mod.members(layout)
        self.assertEqual({m.FluxLumen for m in members}, {1200.0})
        out = os.path.join(work_dir("layout-type"), "layout_type.FCStd")
        doc.saveAs(out)
        name = layout.Name
        FreeCAD.closeDocument(doc.Name)
        again = FreeCAD.openDocument(out)
        layout = again.getObject(name)
        self.assertEqual((layout.FluxLumen, layout.Template.FluxLumen), (1200.0, 1200.0))
        self.assertEqual(layout.PhotometricFile, layout.Template.PhotometricFile)
        self.assertFalse([o.Name for o in again.Objects if "Touched" in o.State])
        FreeCAD.closeDocument(again.Name)
