"""GUI scenario: daylight. From the Start page the user builds the office (a room of Arch walls
with a window in the south wall), switches its luminaires off, adds a *Sky* from the toolbar
(nothing selected: the hosted window becomes its portal on the wall's inner face, pointing
into the room), turns the work-plane grid into a daylight-factor grid with EN 17037's medium
level at 15 900 lx, and runs the analysis from its panel.

The solver traces the grid's daylight factor (the sky through the portal, E_out exact) and
judges EN 17037's D_T and D_TM; the user sees the grid in false colours with the legend in %,
the panel's row "DF x.xx %" and its verdict."""
import json
import os
import sys

from guilib import STATUS, expect, grab_window, log, pump, scenario, toolbar_enabled, wait_until

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_panel(analysis) -> None:
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    before = analysis_panel.last_run()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Run")
    ok = wait_until(lambda: analysis_panel.last_run() is not before
                    and analysis_panel.last_run().stage in ("done", "failed", "cancelled"),
                    120.0)
    job = analysis_panel.last_run()
    expect(ok and job.stage == "done", f"the run did not finish: "
                                       f"{job.stage if job else None} {job.error if job else ''}")
    pump(0.5)


def table_rows() -> dict:
    from lighting.taskpanels import analysis_panel

    panel = analysis_panel.last_panel()
    last = panel.table.columnCount() - 1
    return {panel.table.item(r, 0).text(): (panel.table.item(r, 2).text(),
                                            panel.table.item(r, last).text())
            for r in range(panel.table.rowCount())}


def check_sunlight() -> None:
    """The panel's sunlight line for the south window and the value column's header, which
    names the DF row under it."""
    import re

    from lighting.taskpanels import analysis_panel

    panel = analysis_panel.last_panel()
    view = panel.results_view
    text = view.sunlight.text()
    STATUS["sunlight"] = text
    expect(not view.sunlight.isHidden(), "the sunlight exposure is not shown")
    expect(re.search(r"^Window: \d+ h \d\d min, (none \(under 1.5 h\)|minimum|medium|high)$",
                     text, re.M) is not None, f"no sunlight line for the window: {text!r}")
    header = view.table.horizontalHeaderItem(2).text()
    STATUS["value_header"] = header
    expect("DF %" in header, f"the value column's header {header!r} does not name DF")
    panel.scroll.ensureWidgetVisible(view.sunlight)  # as a user scrolls to it
    pump(0.3)
    grab_window("daylight_sunlight")


def body() -> None:
    import FreeCADGui

    import office_model
    from lighting.objects import luminaire_layout

    doc = office_model.build_office(photons=400000)
    office_model.show_in_gui(doc)
    pump(0.5)
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    analysis.Decide = False
    for lum in luminaire_layout.placed_luminaires(analysis):
        lum.FluxLumen = 0.0  # daylight only
    FreeCADGui.Selection.clearSelection()
    expect(toolbar_enabled("Lighting_Sky"), "the Sky command is not enabled")
    before = {o.Name for o in doc.Objects}
    FreeCADGui.runCommand("Lighting_Sky")
    pump(0.5)
    skies = [doc.getObject(n) for n in {o.Name for o in doc.Objects} - before]
    skies = [o for o in skies if type(getattr(o, "Proxy", None)).__name__ == "Sky"]
    expect(len(skies) == 1, "the Sky command made no sky")
    if not skies:
        return
    sky = skies[0]
    STATUS["portals"] = json.loads(json.dumps(sky.PortalCount))
    expect(sky.PortalCount == 1, f"the window gave {sky.PortalCount} portals")
    expect(sky in analysis.Group, "the sky is not in the active analysis")
    # Double-click: the Sky's panel says what it exports and which glazing defaults it takes.
    sky.ViewObject.Proxy.doubleClicked(sky.ViewObject)
    pump(0.5)
    from lighting.taskpanels import sync

    shown = [p for p in sync.open_panels() if type(p).__name__ == "SkyPanel"]
    expect(len(shown) == 1, "double-clicking the sky opened no panel")
    if shown:
        text = shown[0].text.text()
        STATUS["sky_panel"] = text
        for words in ("Portal 'Window'", "tau_v 0.75", "frame factor 0.8",
                      "maintenance factor 0.9", "left out of the scene"):
            expect(words in text, f"the sky's panel does not say {words!r}: {text}")
        grab_window("daylight_sky_panel")
    grid = doc.getObject("Workplane")
    grid.Quantity = "Daylight factor"
    grid.DaylightLevel = "Medium"
    grid.MedianDiffuseLux = 15900.0
    sky.SunlightExposure = True  # EN 17037 sunlight exposure at the window (property editor)
    doc.recompute()
    run_panel(analysis)
    check_sunlight()
    rows = table_rows()
    STATUS["rows_run"] = rows
    log(f"rows after the run {rows}")
    STATUS["rows"] = rows
    value, verdict = rows.get(grid.Label, ("", ""))
    expect(value.startswith("DF ") and value.endswith(" %"), f"the grid's row shows no DF: {rows}")
    expect(verdict in ("pass", "FAIL", "undecided"), f"the grid's verdict: {rows}")
    legend = analysis.ViewObject.Proxy
    colours = {tuple(round(c, 2) for c in colour[:3]) for colour in grid.ViewObject.DiffuseColor}
    STATUS["grid_colours"] = len(colours)
    expect(len(colours) > 3, f"the DF grid is not painted cell by cell: {len(colours)} colours")
    holder = getattr(legend, "legend_holder", None)
    expect(holder is not None and holder.getNumChildren() == 1, "no legend shown")
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewTop()  # as a user reads a DF plan: from above, through the see-through ceiling
    view.fitAll()
    pump(0.5)
    grab_window("daylight_df", docs_name="daylight-factor.png")


scenario(body)
