"""GUI scenario: discomfort glare. From the Start page the user builds the office, adds an
observer with the toolbar's *Observer* command (nothing selected: seated in the middle of the
room, looking along +X), picks the office preset for its UGR limit, runs the analysis in its
panel and reads the observer's UGR, interval and verdict in the results table. An *Observer
grid* over the model (nothing selected) adds eyes at 1.2 m looking every 90 degrees; its row
shows the maximum UGR."""
import os
import sys

from guilib import STATUS, expect, grab_window, pump, run_and_read_rows, scenario, toolbar_enabled

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))


def body() -> None:
    import FreeCADGui

    import office_model

    doc = office_model.build_office(photons=200000)
    office_model.show_in_gui(doc)
    pump(0.5)
    FreeCADGui.Selection.clearSelection()
    expect(toolbar_enabled("Lighting_Observer"), "the Observer command is not enabled")
    before = {o.Name for o in doc.Objects}
    FreeCADGui.runCommand("Lighting_Observer")
    pump(0.5)
    made = [doc.getObject(n) for n in {o.Name for o in doc.Objects} - before]
    eyes = [o for o in made if type(getattr(o, "Proxy", None)).__name__ == "Observer"]
    expect(len(eyes) == 1, f"Observer made {[o.Name for o in made]}")
    if not eyes:
        return
    eye = eyes[0]
    z_m = eye.Placement.Base.z / 1000.0
    STATUS["eye_m"] = [round(c / 1000.0, 3) for c in eye.Placement.Base]
    expect(abs(z_m - 1.2) < 0.01, f"the eye is not seated at 1.2 m above the floor: {z_m}")
    eye.Activity = "Offices: Writing, typing, reading, data processing"
    expect(float(eye.UgrMax) == 19.0, f"the office preset gave UgrMax {eye.UgrMax}")
    before = {o.Name for o in doc.Objects}
    FreeCADGui.runCommand("Lighting_ObserverGrid")
    pump(0.5)
    grids = [doc.getObject(n) for n in {o.Name for o in doc.Objects} - before]
    grids = [o for o in grids if getattr(o, "GridMode", False)]
    expect(len(grids) == 1, "Observer grid made no grid-mode observer")
    if grids:
        g = grids[0]
        expect(abs(g.Placement.Base.z / 1000.0 - 1.2) < 0.05,
               f"the grid's eyes are not seated: z {g.Placement.Base.z / 1000.0}")
        expect(float(g.GridLength) > 1000.0 and float(g.GridWidth) > 1000.0,
               f"the grid is {g.GridLength} x {g.GridWidth}")
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    analysis.Decide = False
    rows = run_and_read_rows(analysis, 120.0)[1]
    ugr, verdict = rows.get(eye.Label, ("", ""))
    expect(ugr.startswith("UGR"), f"the observer's row shows no UGR: {rows}")
    expect(verdict in ("pass", "FAIL", "undecided"), f"the observer's verdict: {rows}")
    if grids:
        ugr, verdict = rows.get(grids[0].Label, ("", ""))
        expect(ugr.startswith("max UGR"), f"the observer grid's row shows no max UGR: {rows}")
    grab_window("glare", docs_name="glare-observer.png")


scenario(body)
