"""The luminaire library (lighting/luminaire_library.py): the shipped photometric files and a
user folder, each with the native parser's facts; a malformed file listed with its error and
never assigned; assignment and creation as one undo step each."""
import glob
import os
import shutil
import unittest

import FreeCAD

import lighting
from lighting import luminaire_library as library
from lighting.solver import run
from wbtest import REPO, close_all, needs_solver, work_dir

SHIPPED_DIR = os.path.join(REPO, "Resources", "luminaires")
#: Lamp lumens of the shipped files (Resources/luminaires/README.md: lamps x lumens).
README_LUMENS = {"downlight": 1500.0, "wallwasher": 2000.0, "batwing_panel": 3600.0,
                 "linear_tube": 2600.0}
#: A LM-63-2002 file whose sixth line has a vertical angle that is no number.
MALFORMED_IES = ("IESNA:LM-63-2002\n[MANUFAC] Test\nTILT=NONE\n1 1000 1 3 2 1 2 0.1 0.1 0\n"
                 "1 1 10\n0 45 banana\n0 180\n100 50 0\n100 50 0\n")


def shipped_paths():
    return sorted(glob.glob(os.path.join(SHIPPED_DIR, "*.ies")) +
                  glob.glob(os.path.join(SHIPPED_DIR, "*.ldt")))


class LibraryCase(unittest.TestCase):
    def setUp(self):
        self.saved_folder = library.user_folder()
        self.folder = work_dir("library")

    def tearDown(self):
        library.set_user_folder(self.saved_folder)
        close_all()

    def user_folder_with_files(self):
        """A user folder: a copy of a shipped file (upper-case extension), a malformed file,
        and a text file that is no photometry."""
        shutil.copyfile(os.path.join(SHIPPED_DIR, "downlight.ldt"),
                        os.path.join(self.folder, "My_Downlight.LDT"))
        with open(os.path.join(self.folder, "broken.ies"), "w", encoding="ascii") as stream:
            stream.write(MALFORMED_IES)
        with open(os.path.join(self.folder, "notes.txt"), "w", encoding="ascii") as stream:
            stream.write("not photometry\n")
        return self.folder

    def office_luminaires(self, count=2):
        doc = FreeCAD.newDocument("Library")
        doc.UndoMode = 1
        made = [lighting.make_luminaire(doc, (1.0 + i, 1.0, 2.9), flux_lm=5200.0)
                for i in range(count)]
        doc.recompute()
        return doc, made


class ShippedFiles(LibraryCase):
    def test_shipped_folder_is_found(self):
        self.assertEqual(os.path.realpath(library.shipped_folder()), os.path.realpath(SHIPPED_DIR))
        self.assertEqual(len(shipped_paths()), 8)

    @needs_solver
    def test_all_shipped_files_with_the_native_lumens(self):
        module = run.load_module()
        entries = library.list_entries(folder="")
        self.assertEqual([os.path.realpath(e.path) for e in entries],
                         [os.path.realpath(p) for p in shipped_paths()])
        for entry in entries:
            with self.subTest(entry.name):
                self.assertTrue(entry.ok, entry.error)
                self.assertEqual(entry.source, library.SHIPPED)
                native = module.photometry_summary(entry.path)
                self.assertEqual(entry.lamp_lumens_lm, native["lamp_lumens_lm"])
                self.assertEqual(entry.fact("peak_cd"), native["peak_cd"])
                stem = os.path.splitext(entry.name)[0]
                self.assertAlmostEqual(entry.lamp_lumens_lm, README_LUMENS[stem], places=6)
                self.assertTrue(entry.maker, f"{entry.name}: no maker in {entry.keywords}")
                self.assertTrue(entry.luminaire_name)
                self.assertIn(entry.fact("format"), ("ies", "ldt"))

    @needs_solver
    def test_summary_rows(self):
        entry = library.read_entry(os.path.join(SHIPPED_DIR, "downlight.ies"))
        rows = dict(entry.facts())
        self.assertEqual(rows["Lamp lumens"], "1500 lm")
        self.assertEqual(rows["Maker"], "Lighting project")
        self.assertEqual(rows["Symmetry"], "rotational")
        self.assertIn("C0-C180 54.0°", rows["Beam angle"])
        self.assertIn("C0-C180 94.2°", rows["Field angle"])
        # 1671.1 cd from 1500 lm: 1114 cd/klm, the figure DIALux's diagram is scaled in.
        self.assertEqual(rows["Peak"], "1671 cd (1114 cd/klm)")
        self.assertTrue(rows["Format"].startswith("IES LM-63-2002"), rows["Format"])
        tube = dict(library.read_entry(os.path.join(SHIPPED_DIR, "linear_tube.ies")).facts())
        self.assertIn("C90-C270 n/a", tube["Beam angle"])  # no 50 % crossing across the tube


class UserFolder(LibraryCase):
    @needs_solver
    def test_user_folder_from_the_preference(self):
        library.set_user_folder(self.user_folder_with_files())
        entries = library.list_entries()
        user = [e for e in entries if e.source == library.USER]
        self.assertEqual([e.name for e in user], ["broken.ies", "My_Downlight.LDT"])
        self.assertEqual(len(entries), 8 + 2)
        mine = user[1]
        self.assertTrue(mine.ok, mine.error)
        self.assertEqual(mine.lamp_lumens_lm, 1500.0)

    @needs_solver
    def test_malformed_file_is_listed_with_its_error(self):
        entries = library.list_entries(folder=self.user_folder_with_files(), shipped=False)
        broken = [e for e in entries if e.name == "broken.ies"][0]
        self.assertFalse(broken.ok)
        self.assertIn("broken.ies", broken.error)
        self.assertIn("line 6", broken.error)
        self.assertIn("banana", broken.error)
        self.assertEqual(broken.facts(), [("Error", broken.error)])
        self.assertIsNone(broken.lamp_lumens_lm)

    def test_missing_user_folder_lists_the_shipped_files_only(self):
        library.set_user_folder(os.path.join(self.folder, "gone"))
        self.assertEqual(len(library.list_entries()), 8)

    @needs_solver
    def test_malformed_file_cannot_be_assigned(self):
        self.user_folder_with_files()
        doc, (lum, _other) = self.office_luminaires()
        undo_steps = len(doc.UndoNames)
        with self.assertRaises(ValueError) as caught:
            library.assign(doc, [lum], os.path.join(self.folder, "broken.ies"))
        self.assertIn("broken.ies", str(caught.exception))
        self.assertIn("line 6", str(caught.exception))
        self.assertEqual(lum.LuminaireType, "Area")
        self.assertEqual(lum.PhotometricFile, "")
        self.assertEqual(len(doc.UndoNames), undo_steps)
        with self.assertRaises(ValueError):
            library.create(doc, os.path.join(self.folder, "broken.ies"))
        self.assertEqual(len(lighting.luminaire_library.list_entries(self.folder, False)), 2)


class Assignment(LibraryCase):
    @needs_solver
    def test_assign_sets_type_file_and_flux_in_one_undo_step(self):
        doc, made = self.office_luminaires()
        steps = len(doc.UndoNames)
        path = os.path.join(SHIPPED_DIR, "batwing_panel.ldt")
        library.assign(doc, made, path)
        self.assertEqual(len(doc.UndoNames), steps + 1)
        self.assertEqual(doc.UndoNames[0], "Assign luminaire data")
        for lum in made:
            self.assertEqual(lum.LuminaireType, "Photometric")
            self.assertEqual(os.path.realpath(lum.PhotometricFile), os.path.realpath(path))
            self.assertEqual(lum.FluxLumen, 3600.0)
        doc.undo()
        for lum in made:
            self.assertEqual((lum.LuminaireType, lum.FluxLumen, lum.PhotometricFile),
                             ("Area", 5200.0, ""))

    @needs_solver
    def test_keep_own_flux(self):
        doc, made = self.office_luminaires(1)
        library.assign(doc, made, os.path.join(SHIPPED_DIR, "downlight.ies"), keep_flux=True)
        self.assertEqual((made[0].LuminaireType, made[0].FluxLumen), ("Photometric", 5200.0))

    @needs_solver
    def test_assigned_luminaire_exports(self):
        doc, made = self.office_luminaires(1)
        path = os.path.join(SHIPPED_DIR, "wallwasher.ies")
        library.assign(doc, made, path)
        from lighting.objects.luminaire import scene_entry

        entry = scene_entry(made[0])
        self.assertEqual(entry["type"], "photometric")
        self.assertAlmostEqual(entry["flux_lm"], 2000.0 * 0.8)

    def test_non_luminaires_are_refused(self):
        doc, _made = self.office_luminaires(1)
        box = doc.addObject("Part::Box", "Box")
        with self.assertRaises(ValueError) as caught:
            library.assign(doc, [box], os.path.join(SHIPPED_DIR, "downlight.ies"))
        self.assertIn("Box", str(caught.exception))

    @needs_solver
    def test_create_new_luminaire_in_one_undo_step(self):
        doc = FreeCAD.newDocument("Create")
        doc.UndoMode = 1
        analysis = lighting.make_analysis(doc)
        path = os.path.join(SHIPPED_DIR, "linear_tube.ldt")
        lum = library.create(doc, path, position_m=(2.0, 1.5, 2.9), analysis=analysis)
        name = lum.Name
        self.assertEqual(doc.UndoNames, ["Create luminaire"])
        self.assertEqual((lum.LuminaireType, lum.FluxLumen), ("Photometric", 2600.0))
        self.assertIn(lum, analysis.Group)
        self.assertAlmostEqual(lum.Placement.Base.z, 2900.0)
        doc.undo()
        self.assertIsNone(doc.getObject(name))

    @needs_solver
    def test_api_hooks(self):
        doc, made = self.office_luminaires(1)
        names = [e.name for e in lighting.luminaire_library_entries(folder="")]
        self.assertEqual(len(names), 8)
        lighting.assign_photometry(doc, made, os.path.join(SHIPPED_DIR, "downlight.ldt"))
        self.assertEqual(made[0].FluxLumen, 1500.0)


class PolarDiagram(LibraryCase):
    @needs_solver
    def test_headline_ugr_is_the_tables_4h_8h_entry(self):
        """The chooser's UGR line is the solver's CIE 190 table at 4H x 8H, 0.7/0.5/0.2."""
        from lighting.solver import run

        path = os.path.join(SHIPPED_DIR, "downlight.ldt")
        crosswise, endwise = library.headline_ugr(path)
        table = run.load_module().ugr_table(path)
        row = next(r for r in table["rows"] if (r["x_h"], r["y_h"]) == (4.0, 8.0))
        self.assertEqual((crosswise, endwise), (row["crosswise"][0], row["endwise"][0]))
        self.assertTrue(10.0 < crosswise < 35.0)
        self.assertIs(library.ugr_table(path), library.ugr_table(path))  # cached

    @needs_solver
    def test_full_ugr_table_is_the_solvers(self):
        """The chooser's UGR table window shows the solver's 19 x 10 table, one decimal."""
        from lighting.solver import run
        path = os.path.join(SHIPPED_DIR, "batwing_panel.ldt")
        view = library.ugr_table(path)
        table = run.load_module().ugr_table(path)
        texts = library.ugr_table_texts(view)
        self.assertEqual(len(texts), 19)
        for shown, row in zip(texts, table["rows"]):
            self.assertEqual(shown[1], f"{row['y_h']:g}H")
            self.assertEqual(shown[2:], [f"{v:.1f}" for v in row["crosswise"] + row["endwise"]])
        self.assertEqual([t[0] for t in texts if t[0]], ["2H", "4H", "8H", "12H"])
        self.assertIn("S = 0.25 H. Corrections for other spacings are not given.",
                      library.ugr_table_note(view))

    def test_polar_png_from_the_native_plotter(self):
        if run.cli_executable() is None:
            if os.environ.get("LIGHTSOLVER_REQUIRED") == "1":
                self.fail("lightsolver CLI required but not found")
            self.skipTest("lightsolver CLI not found")
        png = library.polar_diagram_png(os.path.join(SHIPPED_DIR, "downlight.ldt"), self.folder)
        with open(png, "rb") as stream:
            self.assertEqual(stream.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertEqual(library.polar_diagram_png(
            os.path.join(SHIPPED_DIR, "downlight.ldt"), self.folder), png)  # cached
        bad = os.path.join(self.folder, "broken.ies")
        with open(bad, "w", encoding="ascii") as stream:
            stream.write(MALFORMED_IES)
        with self.assertRaises(ValueError) as caught:
            library.polar_diagram_png(bad, self.folder)
        self.assertIn("line 6", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
