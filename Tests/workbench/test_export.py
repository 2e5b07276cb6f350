"""Scene export of the example office: triangles, metres, materials, luminaires, targets."""
import json
import math
import os
from unittest import mock

import FreeCAD

import lighting
from lighting.export import collect
from lighting.export.materials import internal_transmittance
from wbtest import (REPO, DocTestCase, build_office, load_scene, mesh, needs_solver, open_edges,
                    triangle_keys, triangle_normals, work_dir)

V = FreeCAD.Vector


class OfficeExport(DocTestCase):
    def setUp(self):
        import office_model

        self.doc = build_office()
        self.names = dict(office_model.OBJECTS)
        self.folder = work_dir("export")
        self.path = lighting.export_scene(self.doc, directory=self.folder)
        self.scene = load_scene(self.path)
        print(f"\nscene file: {self.path}")

    def test_format_and_size(self):
        scene = self.scene
        self.assertEqual(scene["format"], "lightsolver.scene/1")
        self.assertEqual(set(scene), {"format", "materials", "meshes", "luminaires", "targets",
                                      "settings", "metadata"})
        triangles = sum(len(m["triangles"]) for m in scene["meshes"])
        print(f"triangles: {triangles}")
        self.assertGreater(triangles, 100)
        self.assertLess(triangles, 3000)  # the office must stay small
        # The office's work plane has requirements: the run decides them (Photons: the budget).
        self.assertEqual(scene["settings"], {"photons": 100000, "max_bounces": 1000, "seed": 1,
                                             "confidence": 0.95, "decide": True})
        workplane = next(t for t in scene["targets"] if t["name"] == "Workplane")
        self.assertEqual(workplane["requirements"], {"em_lux": 500.0, "u0": 0.6})
        self.assertEqual(len({m["name"] for m in scene["meshes"]}), len(scene["meshes"]))
        for m in scene["meshes"]:
            self.assertIn(m["material"], scene["materials"])
            n = len(m["vertices"])
            for tri in m["triangles"]:
                self.assertTrue(all(0 <= i < n for i in tri))
        self.assertEqual(self.doc.getObject(self.names["analysis"]).SceneFile, self.path)

    def test_units_are_metres(self):
        lows, highs = [1e9] * 3, [-1e9] * 3
        for m in self.scene["meshes"]:
            for p in m["vertices"]:
                for i in range(3):
                    lows[i], highs[i] = min(lows[i], p[i]), max(highs[i], p[i])
        # Walls 0.2 m thick around 5 x 4 m, floor slab from -0.2 m, ceiling slab to 3.2 m.
        for got, want in zip(lows + highs, [-0.2, -0.2, -0.2, 5.2, 4.2, 3.2]):
            self.assertAlmostEqual(got, want, 6)

    def test_exported_objects(self):
        exported = {o.Name for o in collect.exported_objects(self.doc)}
        n = self.names
        for role in ("walls", "floor", "ceiling", "window", "desk", "cabinet"):
            self.assertIn(n[role], exported)
        # Consumed inputs, the space, the wall outline and Lighting objects stay out.
        for name in ("DeskTop", "DeskSideL", "DeskSideR", "RoomVolume", n["space"],
                     "Luminaire01", "Workplane", n["analysis"], "CeilingDomain"):
            self.assertNotIn(name, exported)

    def test_materials(self):
        scene, n = self.scene, self.names
        mats = scene["materials"]

        def material_of(mesh_name):
            return mats[mesh(scene, mesh_name)["material"]]
        self.assertEqual(material_of(n["walls"]), {"type": "diffuse", "reflectance": 0.5})
        self.assertEqual(material_of(f"{n['ceiling']}.default_ceiling")["reflectance"], 0.7)
        self.assertEqual(material_of(f"{n['floor']}.default_floor")["reflectance"], 0.2)
        self.assertEqual(material_of(n["desk"]), {"type": "diffuse", "reflectance": 0.45})
        self.assertEqual(material_of(n["cabinet"])["reflectance"], 0.5)
        glass = material_of(f"{n['window']}.default_glass")
        self.assertEqual(glass["type"], "glass")
        self.assertFalse(glass["thin"])  # the Arch glass panel is a 10 mm solid
        self.assertAlmostEqual(glass["transmittance"], internal_transmittance(0.9), 12)
        # Total pane transmittance from the internal one: T = tau(1-R)^2 / (1 - R^2 tau^2).
        r, tau = (0.52 / 2.52) ** 2, glass["transmittance"]
        self.assertAlmostEqual(tau * (1 - r) ** 2 / (1 - r * r * tau * tau), 0.9, 9)
        self.assertEqual(material_of(f"{n['window']}.default_frame")["type"], "diffuse")
        # The ceiling slab's underside faces down into the room.
        for normal, _ in triangle_normals(mesh(scene, f"{n['ceiling']}.default_ceiling")):
            self.assertAlmostEqual(normal[2], -1.0, 9)

    def test_luminaires(self):
        lums = self.scene["luminaires"]
        self.assertEqual(len(lums), 4)
        for lum in lums:
            self.assertEqual(lum["type"], "area")
            self.assertAlmostEqual(lum["flux_lm"], 5200.0 * 0.8, 9)
            self.assertAlmostEqual(lum["corner"][2], 2.95, 9)
            e1, e2 = V(*lum["edge1"]), V(*lum["edge2"])
            self.assertAlmostEqual(e1.cross(e2).normalize().z, -1.0, 9)
        meta = self.scene["metadata"]["luminaires"]["Luminaire01"]
        self.assertEqual(meta, {"flux_lm_initial": 5200.0, "maintenance_factor": 0.8})

    def test_face_targets_not_doubled(self):
        scene, n = self.scene, self.names
        targets = {t["name"]: t for t in scene["targets"]}
        self.assertEqual(targets["Workplane"]["type"], "grid")
        desk_t = mesh(scene, targets[n["desk_target"]]["mesh"])
        wall_t = mesh(scene, targets[n["wall_target"]]["mesh"])
        # Desk top 1.6 x 0.8 m facing up; north wall inner face 5 x 3 m facing -y.
        normals = triangle_normals(desk_t)
        self.assertAlmostEqual(sum(a for _, a in normals), 1.28, 9)
        self.assertTrue(all(abs(nrm[2] - 1.0) < 1e-9 for nrm, _ in normals))
        normals = triangle_normals(wall_t)
        self.assertAlmostEqual(sum(a for _, a in normals), 15.0, 9)
        self.assertTrue(all(abs(nrm[1] + 1.0) < 1e-9 for nrm, _ in normals))
        self.assertEqual(desk_t["material"], mesh(scene, n["desk"])["material"])
        self.assertEqual(wall_t["material"], mesh(scene, n["walls"])["material"])
        # No triangle appears twice anywhere in the scene.
        keys = [k for m in scene["meshes"] for k in triangle_keys(m)]
        self.assertEqual(len(keys), len(set(keys)))
        # The wall and the desk stay closed with their target faces put back.
        self.assertEqual(open_edges([mesh(scene, n["walls"]), wall_t]), 0)
        self.assertGreater(open_edges([mesh(scene, n["walls"])]), 0)
        self.assertEqual(open_edges([mesh(scene, n["desk"]), desk_t]), 0)
        self.assertEqual(open_edges([mesh(scene, n["cabinet"])]), 0)

    def test_placement_domain_metadata(self):
        domains = self.scene["metadata"]["placement_domains"]
        self.assertEqual(len(domains), 1)
        self.assertEqual(domains[0]["template"], "Luminaire01")
        self.assertTrue(all(abs(p[2] - 2.95) < 1e-9 for p in domains[0]["candidates"]))

    def test_ply_storage(self):
        folder = work_dir("ply")
        path = lighting.export_scene(self.doc, directory=folder, storage="PLY")
        with open(path, encoding="utf-8") as stream:
            raw = json.load(stream)
        self.assertTrue(all("file" in m and "vertices" not in m for m in raw["meshes"]))
        for m in raw["meshes"]:
            self.assertTrue(os.path.exists(os.path.join(folder, m["file"])))
        ply_scene = load_scene(path)
        for a, b in zip(self.scene["meshes"], ply_scene["meshes"]):
            self.assertEqual(a["name"], b["name"])
            self.assertEqual([list(t) for t in b["triangles"]], a["triangles"])
            self.assertEqual([list(p) for p in b["vertices"]], a["vertices"])


class ShapesAndDeflection(DocTestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("Shapes")
        self.analysis = lighting.make_analysis(self.doc)
        lighting.make_luminaire(self.doc, (0, 0, 3), kind="Point")

    def _export(self):
        from lighting.export.scene import build_scene

        return build_scene(self.analysis)

    def test_deflection_controls_curved_surfaces(self):
        column = self.doc.addObject("Part::Cylinder", "Column")
        column.Radius, column.Height = 500, 2800
        floor = self.doc.addObject("Part::Box", "Floor")
        floor.Length = floor.Width = 2000
        floor.Height = 10
        self.doc.recompute()
        lighting.make_grid_target(self.doc, floor, wall_band_m=0.0)
        self.doc.recompute()
        counts = []
        for deflection in (20.0, 2.0, 0.5):
            self.analysis.LinearDeflection = deflection
            result = self._export()
            counts.append(sum(result.mesh_triangles[m] for m in result.object_meshes["Column"]))
        self.assertLess(counts[0], counts[1])
        self.assertLess(counts[1], counts[2])

    def test_thin_glass_pane_and_properties(self):
        pane = self.doc.addObject("Part::Plane", "Pane")
        pane.Length, pane.Width = 1000, 1000
        pane.addProperty("App::PropertyFloat", "Transmittance", "Lighting")
        pane.Transmittance = 0.8
        wall = self.doc.addObject("Part::Box", "Panel")
        wall.Placement.Base = V(2000, 0, 0)
        wall.addProperty("App::PropertyFloat", "Reflectance", "Lighting")
        wall.Reflectance = 0.35
        self.doc.recompute()
        lighting.make_face_target(self.doc, [(wall, "Face1")])
        self.doc.recompute()
        result = self._export()
        mats = result.scene["materials"]
        pane_mat = [m for m in result.scene["meshes"] if m["name"] == "Pane"][0]["material"]
        self.assertEqual(mats[pane_mat]["type"], "glass")
        self.assertTrue(mats[pane_mat]["thin"])  # a single face: a thin pane
        self.assertAlmostEqual(mats[pane_mat]["transmittance"], internal_transmittance(0.8), 12)
        panel_mat = [m for m in result.scene["meshes"] if m["name"] == "Panel"][0]["material"]
        self.assertEqual(mats[panel_mat], {"type": "diffuse", "reflectance": 0.35})

    def test_arch_material_reflectance(self):
        from lighting.compat import import_arch

        arch = import_arch()
        box = self.doc.addObject("Part::Box", "Base")
        self.doc.recompute()
        wall = arch.makeWall(box)
        material = arch.makeMaterial("Plaster")
        material.Material = dict(material.Material, Reflectance="80 %")
        wall.Material = material
        self.doc.recompute()
        lighting.make_face_target(self.doc, [(wall, "Face1")])
        self.doc.recompute()
        result = self._export()
        entry = [m for m in result.scene["meshes"] if m["name"] == wall.Name][0]
        self.assertEqual(result.scene["materials"][entry["material"]],
                         {"type": "diffuse", "reflectance": 0.8})

    def test_hidden_objects_exported_excluded_not(self):
        box = self.doc.addObject("Part::Box", "Hidden")
        self.doc.recompute()
        box.Visibility = False
        shown = self.doc.addObject("Part::Box", "Shown")
        left = self.doc.addObject("Part::Box", "Excluded")
        self.doc.recompute()
        lighting.exclude(left)
        lighting.make_face_target(self.doc, [(shown, "Face6")])
        self.doc.recompute()
        exported = self._export().object_meshes
        self.assertIn("Hidden", exported)  # visibility is a viewing choice, not physics
        self.assertIn("Shown", exported)
        self.assertNotIn("Excluded", exported)

    def test_global_placement_in_container(self):
        part = self.doc.addObject("App::Part", "Container")
        part.Placement.Base = V(10000, 0, 0)
        box = self.doc.addObject("Part::Box", "Inner")
        part.addObject(box)
        self.doc.recompute()
        lighting.make_face_target(self.doc, [(box, "Face6")])
        self.doc.recompute()
        result = self._export()
        inner = [m for m in result.scene["meshes"] if m["name"] in result.object_meshes["Inner"]]
        self.assertAlmostEqual(min(p[0] for m in inner for p in m["vertices"]), 10.0, 9)
        target = [m for m in result.scene["meshes"] if m["name"].endswith(".faces")][0]
        self.assertAlmostEqual(min(p[0] for p in target["vertices"]), 10.0, 9)
        self.assertTrue(math.isclose(target["vertices"][0][2], 0.01, abs_tol=1e-9))


class Photometric(DocTestCase):
    """IES/LDT luminaires: flux (file or override) x MF, C0 orientation, file copied."""

    def setUp(self):
        self.doc = FreeCAD.newDocument("Photometric")
        floor = self.doc.addObject("Part::Box", "Floor")
        floor.Length = floor.Width = 4000
        floor.Height = 10
        self.doc.recompute()
        lighting.make_analysis(self.doc)
        self.lum = lighting.make_luminaire(self.doc, (2.0, 2.0, 3.0), kind="Photometric",
                                           flux_lm=0.0, maintenance_factor=0.8)
        self.lum.PhotometricFile = os.path.join(REPO, "Resources", "luminaires", "wallwasher.ldt")
        lighting.make_grid_target(self.doc, floor, height_m=0.0, wall_band_m=0.0, spacing_m=0.5)
        self.doc.recompute()

    def _luminaire(self):
        folder = work_dir("photometric")
        path = lighting.export_scene(self.doc, directory=folder)
        with open(path, encoding="utf-8") as stream:
            entry = json.load(stream)["luminaires"][0]
        self.assertTrue(os.path.exists(os.path.join(folder, entry["file"])))
        return entry

    def test_file_flux_and_orientation(self):
        entry = self._luminaire()
        self.assertEqual(entry["type"], "photometric")
        self.assertAlmostEqual(entry["flux_lm"], 2000.0 * 0.8)  # the LDT's lamp set x MF
        self.assertEqual(entry["aim"], [0.0, 0.0, -1.0])
        self.assertEqual(entry["rotation_deg"], 0.0)
        self.assertTrue(entry["file"].startswith("photometry/"))
        # Turn the luminaire 90 deg about z: its C0 (local +X) now points to +y, which the
        # scene says as 90 deg counter-clockwise seen from above.
        self.lum.Placement.Rotation = FreeCAD.Rotation(V(0, 0, 1), 90).multiply(
            self.lum.Placement.Rotation)
        self.doc.recompute()
        self.assertAlmostEqual(self._luminaire()["rotation_deg"], 90.0, 9)
        # Aimed along +x (a wall washer on a side wall), C0 up: the default is +y, -90 deg.
        self.lum.Placement.Rotation = FreeCAD.Rotation(V(0, 0, -1), V(1, 0, 0))
        self.doc.recompute()
        c0 = self.lum.Placement.Rotation.multVec(V(1, 0, 0))
        entry = self._luminaire()
        self.assertEqual([round(x, 9) for x in entry["aim"]], [1.0, 0.0, 0.0])
        ref, aim = V(0, 1, 0), V(*entry["aim"])
        a = math.radians(entry["rotation_deg"])
        solver_c0 = ref * math.cos(a) + ref.cross(aim) * math.sin(a)
        self.assertAlmostEqual((solver_c0 - c0).Length, 0.0, 9)

    def test_flux_override_and_ies(self):
        self.lum.PhotometricFile = os.path.join(REPO, "Resources", "luminaires", "downlight.ies")
        self.assertAlmostEqual(self._luminaire()["flux_lm"], 1500.0 * 0.8)
        self.lum.FluxLumen = 1000.0
        self.assertAlmostEqual(self._luminaire()["flux_lm"], 800.0)

    def test_missing_file_is_an_error(self):
        self.lum.PhotometricFile = "/nonexistent/lamp.ies"
        report = lighting.check(self.doc, need_solver=False)
        self.assertTrue(any("not found" in m.text for m in report.errors), report.format())

    def test_lamp_lumens_come_from_the_solver(self):
        """lighting.photometry does not parse files: without the module, a luminaire that needs
        the file's lamp lumens cannot be exported, and the error says why."""
        from lighting.messages import SolverUnavailableError
        from lighting.solver import run

        with mock.patch.object(run, "load_module",
                               side_effect=SolverUnavailableError("lightsolver missing (test)")):
            with self.assertRaises(lighting.CheckError) as ctx:
                lighting.export_scene(self.doc, directory=work_dir("photometric-nosolver"))
        self.assertIn("lightsolver cannot be imported", str(ctx.exception))
        self.assertIn("lightsolver missing (test)", str(ctx.exception))

    @needs_solver
    def test_broken_file_is_named_with_its_line(self):
        path = os.path.join(work_dir("photometric-broken"), "broken.ies")
        with open(os.path.join(REPO, "Resources", "luminaires", "downlight.ies"),
                  encoding="latin-1") as stream:
            lines = stream.read().splitlines()
        tilt = next(i for i, line in enumerate(lines) if line.startswith("TILT="))
        lines[tilt + 1] = "1 one 1 3 1 1 2 0 0 0"  # lumens per lamp is not a number
        with open(path, "w", encoding="latin-1") as stream:
            stream.write("\n".join(lines) + "\n")
        self.lum.PhotometricFile = path
        self.lum.FluxLumen = 1000.0  # the file is then read by the solver's check only
        report = lighting.check(self.doc, need_solver=False)
        errors = [m for m in report.errors]
        self.assertEqual(len(errors), 1, report.format())
        self.assertEqual(errors[0].object_name, self.lum.Name)
        self.assertIn(f"broken.ies, line {tilt + 2}", errors[0].text)


class ArchElements(DocTestCase):
    """Stairs, roofs and equipment (furniture) are exported with sensible materials."""

    def test_stairs_roof_furniture(self):
        from lighting.compat import import_arch
        from lighting.export.scene import build_scene
        import Draft

        arch = import_arch()
        doc = FreeCAD.newDocument("Arch")
        stairs = arch.makeStairs(length=3000, width=1000, height=2800, steps=14)
        outline = Draft.makeWire([V(0, 0, 3000), V(4000, 0, 3000), V(4000, 3000, 3000),
                                  V(0, 3000, 3000)], closed=True)
        doc.recompute()
        roof = arch.makeRoof(outline, angles=[30, 30, 30, 30])
        chair = doc.addObject("Part::Box", "ChairBox")
        doc.recompute()
        equipment = arch.makeEquipment(chair)
        analysis = lighting.make_analysis(doc)
        lighting.make_luminaire(doc, (2.0, 1.5, 2.5), kind="Point")
        lighting.make_face_target(doc, [(stairs, "Face1")])
        doc.recompute()
        result = build_scene(analysis)
        self.assertTrue(result.report.ok, result.report.format())
        meshes = result.object_meshes
        self.assertIn(stairs.Name, meshes)
        self.assertIn(f"{roof.Name}.default_ceiling", meshes[roof.Name])  # its underside
        self.assertEqual(meshes[equipment.Name], [equipment.Name])
        self.assertNotIn(chair.Name, meshes)  # consumed by the equipment
        mats = result.scene["materials"]
        entry = [m for m in result.scene["meshes"] if m["name"] == equipment.Name][0]
        self.assertEqual(mats[entry["material"]], {"type": "diffuse", "reflectance": 0.5})
