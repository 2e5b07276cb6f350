"""lighting.LiveSession headless: first numbers arrive; a luminaire moved through the API
brightens the cell under its new position and darkens the one it left within a bounded number
of batches, without re-export; undo restores the first numbers bit for bit; other edits
re-export; no frame of an older model revision is ever delivered."""
import FreeCAD

import lighting
from lighting.objects import target as target_mod
import os

from wbtest import DocTestCase, build_office, needs_solver, work_dir

V = FreeCAD.Vector
PHOTONS = 1 << 18  # the goal: 32k, 64k, 128k, 256k photons, then idle
MAX_FRAMES = 6     # a change must show within this many batches


def cells(frame, grid_name):
    """(lux, ci_low, ci_high) per cell of the grid target in a frame."""
    tgt = next(t for t in frame.data["targets"] if t["name"] == grid_name)
    return [(c["lux"], c["ci_low_lux"], c["ci_high_lux"]) for c in tgt["cells"]]


def cell_under(grid, x_mm, y_mm):
    """Index of the grid cell under a point (cells row by row along edge1)."""
    iu = int((x_mm - grid.corner.x) / grid.edge1.x * grid.nu)
    iv = int((y_mm - grid.corner.y) / grid.edge2.y * grid.nv)
    return iv * grid.nu + iu


class Live(DocTestCase):
    def setUp(self):
        self.doc = build_office(photons=PHOTONS)
        self.doc.UndoMode = 1
        analysis = self.doc.getObject("LightingAnalysis")
        analysis.TargetAccuracy = 0.0
        analysis.Decide = False
        self.grid_obj = self.doc.getObject("Workplane")
        self.grid = target_mod.grid_rectangle(self.grid_obj)
        self.seen = []

    def finished_frame(self, live, revision):
        """Frames until the one that reaches the goal; every frame is of `revision`."""
        for _ in range(8):
            frame = live.next_frame(timeout=120)
            self.assertIsNotNone(frame, "no frame within 120 s")
            self.seen.append(frame)
            self.assertEqual(frame.revision, live.revision)
            self.assertEqual(frame.revision, revision)
            if frame.finished:
                return frame
        self.fail("the session did not reach its goal")

    @needs_solver
    def test_move_refine_undo(self):
        live = lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0)
        try:
            first = live.next_frame(timeout=120)
            self.assertIsNotNone(first)
            print(f"\nfirst numbers {first.seconds_since_change:.2f} s after the start "
                  f"({first.photons} photons)")
            self.assertEqual((first.revision, first.photons, first.path), (0, 1 << 15, "export"))
            before = self.finished_frame(live, 0)
            self.assertEqual(before.photons, PHOTONS)
            self.assertIsNone(live.next_frame(timeout=0.5), "idle once the goal is reached")

            lum = self.doc.getObject("Luminaire01")
            old_xy, new_xy = (1250.0, 1000.0), (2500.0, 2000.0)
            left, under = cell_under(self.grid, *old_xy), cell_under(self.grid, *new_xy)
            self.doc.openTransaction("Move luminaire")
            lum.Placement.Base = V(new_xy[0], new_xy[1], lum.Placement.Base.z)
            self.doc.commitTransaction()
            old = cells(before, self.grid_obj.Name)
            shown = None
            for count in range(1, MAX_FRAMES + 1):
                frame = live.next_frame(timeout=120)
                self.assertEqual((frame.revision, frame.path), (1, "luminaires"))
                now = cells(frame, self.grid_obj.Name)
                if now[under][1] > old[under][2] and now[left][2] < old[left][1]:
                    shown = count
                    break
            self.assertIsNotNone(shown, "the move did not show within the bounded batches")
            print(f"move shown after {shown} batch(es), {frame.photons} photons, "
                  f"{frame.seconds_since_change:.2f} s after the change")
            self.finished_frame(live, 1)

            self.doc.undo()
            self.assertEqual(lum.Placement.Base.x, old_xy[0])
            restored = self.finished_frame(live, 2)
            self.assertEqual(restored.path, "luminaires")
            # Same luminaires, seed and photons: photon i is photon i, so the same numbers.
            self.assertEqual(cells(restored, self.grid_obj.Name), old)

            # Anything but luminaires re-exports.
            self.doc.getObject("Desk").Reflectance = 0.8
            self.assertEqual(self.finished_frame(live, 3).path, "export")
        finally:
            live.stop()
        revisions = [f.revision for f in self.seen]
        self.assertEqual(revisions, sorted(revisions))

    @needs_solver
    def test_no_frame_from_before_a_change_made_while_refining(self):
        self.doc.getObject("LightingAnalysis").Photons = 1 << 24  # refines for a while
        live = lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0)
        try:
            self.assertEqual(live.next_frame(timeout=120).revision, 0)
            lum = self.doc.getObject("Luminaire02")
            lum.FluxLumen = 0.5 * lum.FluxLumen  # batches of revision 0 are in flight
            for _ in range(3):
                frame = live.next_frame(timeout=120)
                self.assertEqual((frame.revision, frame.path), (1, "luminaires"))
            self.assertEqual(frame.photons, 1 << 17)  # started again at photon 0
        finally:
            live.stop()

    @needs_solver
    def test_furniture_moved_as_an_instance_agrees_with_a_fresh_export(self):
        """The cabinet (a mesh no target refers to) moves as an instance, no re-export; the
        numbers agree with a session that exports the moved model (cells within 5 sigma: an
        instance transform rounds in float, baked vertices in double)."""
        live = lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0)
        try:
            before = self.finished_frame(live, 0)
            cabinet = self.doc.getObject("Cabinet")
            xy = (2000.0, 1500.0)
            cabinet.Placement.Base = V(xy[0], xy[1], cabinet.Placement.Base.z)
            moved = self.finished_frame(live, 1)
            self.assertEqual(moved.path, "instances")
        finally:
            live.stop()
        with lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0) as fresh_live:
            fresh = next(f for f in fresh_live if f.finished)  # iterating: frames until then
            self.assertEqual((fresh.revision, fresh.path), (0, "export"))
        name = self.grid_obj.Name
        a, b, old = cells(moved, name), cells(fresh, name), cells(before, name)
        for (ma, la, ha), (mb, lb, hb) in zip(a, b):
            sigma = ((ha - la) ** 2 + (hb - lb) ** 2) ** 0.5 / (2 * 1.96)
            self.assertLessEqual(abs(ma - mb), 5 * sigma + 1e-9)
        under = cell_under(self.grid, *xy)
        self.assertLess(a[under][2], old[under][1], "the cabinet does not shade its new place")

    @needs_solver
    def test_dragging_restarts_once_when_it_stops(self):
        """Ten moves 50 ms apart (a drag) with the GUI's polling in between: no restart while
        they come, one once they have been quiet for the debounce."""
        import time

        with lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0) as live:
            self.finished_frame(live, 0)
            lum = self.doc.getObject("Luminaire04")
            for _ in range(10):
                lum.Placement.Base = lum.Placement.Base + V(-100.0, 0.0, 0.0)
                self.assertFalse(live.poll())
                self.assertIsNone(live.take_frame())
                time.sleep(0.05)
            self.assertEqual(live.revision, 0)
            frame = live.next_frame(timeout=120)
            self.assertEqual((live.revision, frame.revision, frame.path), (1, 1, "luminaires"))

    @needs_solver
    def test_a_model_that_does_not_export_pauses_until_it_does(self):
        with lighting.LiveSession(self.doc, first_photons=1 << 15, threads=0) as live:
            first = self.finished_frame(live, 0)
            lum = self.doc.getObject("Luminaire03")
            lum.LuminaireType = "Photometric"  # without a file: the export fails
            self.assertIsNone(live.next_frame(timeout=1.0))
            self.assertIsInstance(live.error, lighting.CheckError)
            self.assertEqual(live.revision, 1)
            lum.LuminaireType = "Area"  # back to the kept scene: it traces again
            again = self.finished_frame(live, 2)
            self.assertIsNone(live.error)
            self.assertEqual(cells(again, self.grid_obj.Name), cells(first, self.grid_obj.Name))

    def test_live_is_not_saved(self):
        """Live is a GUI state: a reopened file starts with it off."""
        self.doc.getObject("LightingAnalysis").Live = True
        path = os.path.join(work_dir("live-save"), "office.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        self.assertFalse(self.doc.getObject("LightingAnalysis").Live)
