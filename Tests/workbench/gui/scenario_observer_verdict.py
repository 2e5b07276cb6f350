"""GUI scenario: a new observer's verdict is never blank. In the office (whose grids have no
EN 12464-1 activity yet) the toolbar's *Observer* makes an eye without a UGR limit: its row
says "no limit set". The user then picks the workplane's activity (an office task, UGR_L 19)
in the property editor; a second *Observer* takes that limit from the analysis' activity, and
after a run its row shows its UGR and a verdict."""
import os
import sys

from guilib import STATUS, expect, grab_window, pump, run_and_read_rows, scenario

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))

OFFICE = "Offices: Writing, typing, reading, data processing"


def add_observer(doc):
    import FreeCADGui

    before = {o.Name for o in doc.Objects}
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Observer")
    pump(0.5)
    made = [doc.getObject(n) for n in {o.Name for o in doc.Objects} - before]
    eyes = [o for o in made if type(getattr(o, "Proxy", None)).__name__ == "Observer"]
    expect(len(eyes) == 1, f"Observer made {[o.Name for o in made]}")
    return eyes[0] if eyes else None


def body() -> None:
    import office_model

    doc = office_model.build_office(photons=100000)
    office_model.show_in_gui(doc)
    pump(0.5)
    plain = add_observer(doc)
    expect(plain is not None and float(plain.UgrMax) == 0.0,
           f"without an activity the new observer has UgrMax {getattr(plain, 'UgrMax', None)}")
    workplane = [o for o in doc.Objects if o.Label == "Workplane"][0]
    workplane.Activity = OFFICE  # the property editor's choice
    doc.recompute()
    eye = add_observer(doc)
    if plain is None or eye is None:
        return
    STATUS["observer"] = {"activity": eye.Activity, "ugr_max": float(eye.UgrMax)}
    expect(eye.Activity == OFFICE and float(eye.UgrMax) == 19.0,
           f"the new observer did not take the analysis' activity: {STATUS['observer']}")
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    panel, rows = run_and_read_rows(analysis, 180.0)
    ugr, verdict = rows.get(eye.Label, ("", ""))
    expect(ugr.startswith("UGR"), f"the new observer's row shows no UGR: {rows}")
    expect(verdict in ("pass", "FAIL", "undecided"), f"the new observer's verdict: {rows}")
    expect(rows.get(plain.Label, ("", ""))[1] == "no limit set",
           f"the observer without a limit does not say so: {rows}")
    panel.scroll.ensureWidgetVisible(panel.table)
    grab_window("observer_verdict")


scenario(body)
