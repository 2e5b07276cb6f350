"""GUI scenario: annual daylight. From the Start page the user builds the office (a room of
Arch walls with a window in the south wall and a work-plane grid), adds a *Sky* from the
toolbar (the window becomes its portal), then *Annual daylight* from the toolbar: its panel
opens, the user enters the Chicago weather file, and presses Run (100 000 photons, set in the
property editor, so the year takes seconds).

The year is traced on a worker thread; checked: the panel's lines (sDA300/50% with its interval
and LM-83 verdicts, ASE, UDI, EN 17037, the weather file's hash), the work plane painted cell by
cell with the DA300 map and its legend (screenshot from above, ``annual_da``), then the sDA
verdict map (three colours at most: pass, undecided, fail)."""
import hashlib
import os
import sys

from guilib import STATUS, expect, grab_window, log, pump, scenario, toolbar_enabled, wait_until

SOURCE = os.environ.get("LIGHTING_SOURCE_DIR", ".")
sys.path.insert(0, os.path.join(SOURCE, "Examples"))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHICAGO = os.path.join(SOURCE, "Tests/native/sun/data/"
                               "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")


def colours_of(grid) -> set:
    return {tuple(round(c, 2) for c in colour[:3]) for colour in grid.ViewObject.DiffuseColor}


def body() -> None:
    import FreeCADGui

    import office_model
    from lighting import annual_results
    from lighting.objects import annual as annual_mod
    from lighting.taskpanels import annual_panel

    doc = office_model.build_office(photons=20000)
    office_model.show_in_gui(doc)
    pump(0.5)
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Sky")
    pump(0.3)
    expect(toolbar_enabled("Lighting_AnnualDaylight"), "the Annual daylight command is not "
                                                       "enabled")
    FreeCADGui.runCommand("Lighting_AnnualDaylight")
    pump(0.5)
    made = annual_mod.of_analysis(analysis)
    expect(len(made) == 1, "the command made no annual daylight analysis in the analysis")
    panel = annual_panel.last_panel()
    expect(panel is not None and panel.annual is made[0], "its panel did not open")
    if not made or panel is None:
        return
    annual = made[0]
    annual.Photons = 100000  # the property editor: a quick year
    panel.weather.setText(CHICAGO)  # typed into the panel's Weather field
    panel.weather.editingFinished.emit()
    pump(0.2)
    expect(annual.WeatherFile == CHICAGO, f"the weather file was not taken: {annual.WeatherFile}")
    panel.run_button.click()
    ok = wait_until(lambda: panel.job is None and panel.last_job is not None, 120.0)
    expect(ok and annual.Status == "done", f"the year did not finish: {annual.Status} "
                                           f"{panel.status.text()}")
    pump(0.5)
    text = panel.lines.toPlainText()
    STATUS["lines"] = text
    digest = hashlib.sha256(open(CHICAGO, "rb").read()).hexdigest()
    for words in ("sDA300/50%: ", "LM-83 nominal", "ASE1000,250h: ", "mean UDI 100-2000 lx",
                  "EN 17037 minimum", digest[:16]):
        expect(words in text, f"the panel does not say {words!r}: {text}")
    grid = doc.getObject(office_model.OBJECTS["workplane"])
    colours = colours_of(grid)
    STATUS["da_colours"] = len(colours)
    expect(len(colours) > 3, f"the DA300 map is not painted cell by cell: {len(colours)} colours")
    holder = getattr(analysis.ViewObject.Proxy, "legend_holder", None)
    expect(holder is not None and holder.getNumChildren() == 1, "no legend shown")
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewTop()
    view.fitAll()
    pump(0.5)
    grab_window("annual_da")
    panel.map.setCurrentIndex(list(annual_mod.MAPS).index("sDA verdict"))  # as a user picks it
    pump(0.5)
    verdict_colours = {tuple(round(c, 2) for c in rgb)
                       for rgb in annual_results.VERDICT_COLOUR.values()}
    shown = colours_of(grid)
    STATUS["verdict_colours"] = sorted(shown)
    expect(annual.Map == "sDA verdict", "the map choice did not reach the object")
    expect(shown <= verdict_colours, f"the sDA map shows other colours: {shown}")
    grab_window("annual_sda")
    log("annual scenario done")


scenario(body)
