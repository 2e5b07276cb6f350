"""GUI scenario: light scenes. From the Start page the user builds the office, puts the two
window-side luminaires in a control group, makes a light scene with the toolbar's *Light
scene* command, runs the analysis once, then dims the window row to 30 % and switches the
back row off in the panel's Light scenes section: the Em in the table and the colours follow
at once, with no new run, and *As traced* brings the full values back. The office also has a
glare observer grid: its UGR is rescaled with the rest (it once kept any scene from showing)."""
import os
import sys

from guilib import STATUS, expect, grab_window, log, pump, scenario, toolbar_enabled, wait_until

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))


def _em(panel, label: str) -> float:
    for r in range(panel.table.rowCount()):
        if panel.table.item(r, 0).text() == label:
            return float(panel.table.item(r, 2).text())
    return float("nan")


def body() -> None:
    import FreeCADGui

    import office_model
    from lighting.objects import light_scene
    from lighting.objects import results as results_obj
    from lighting.taskpanels import analysis_panel

    doc = office_model.build_office(photons=200000)
    office_model.show_in_gui(doc)
    pump(0.5)
    for name, group in (("Luminaire01", "Window row"), ("Luminaire02", "Window row"),
                        ("Luminaire03", "Back row"), ("Luminaire04", "Back row")):
        doc.getObject(name).ControlGroup = group
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    analysis.Decide = False
    import lighting

    eyes = lighting.make_observer(doc, (1.0, 1.0, 1.2), ugr_max=19.0, name="EyeGrid",
                                  analysis=analysis)
    eyes.GridMode, eyes.GridLength, eyes.GridWidth = True, 3000.0, 2000.0
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    expect(toolbar_enabled("Lighting_LightScene"), "the Light scene command is not enabled")
    FreeCADGui.runCommand("Lighting_LightScene")
    pump(0.5)
    scenes = light_scene.scenes(analysis)
    expect(len(scenes) == 1 and analysis.Contributions, "the command made no light scene")
    if not scenes:
        return
    before = analysis_panel.last_run()  # a finished earlier run is not this one
    FreeCADGui.runCommand("Lighting_Run")
    ok = wait_until(lambda: analysis_panel.last_run() is not None
                    and analysis_panel.last_run() is not before
                    and analysis_panel.last_run().finished, 120.0)
    expect(ok, "the run did not finish")
    pump(0.5)
    panel = analysis_panel.last_panel()
    results = results_obj.of_analysis(analysis)
    photons, full = results.Photons, _em(panel, "Workplane")
    view = panel.scene_view
    expect(view.table.rowCount() == 2, f"the Light scenes table has {view.table.rowCount()} rows")
    view.table.cellWidget(0, 1).setValue(30.0)  # the window row
    pump(0.3)
    view.table.cellWidget(1, 1).setValue(0.0)   # the back row
    pump(0.5)
    dimmed = _em(panel, "Workplane")
    STATUS["em_full"], STATUS["em_dimmed"] = full, dimmed
    STATUS["shown"] = results.LightScene
    log(f"Em full {full}, dimmed {dimmed}; {results.LightScene}")
    expect(results.Photons == photons, "changing a level traced again")
    expect(0.0 < dimmed < 0.5 * full, f"dimming did not lower Em: {full} -> {dimmed}")
    expect("Window row 30 %" in results.LightScene and "Back row off" in results.LightScene,
           f"the results show {results.LightScene!r}")
    grid = next((t for t in results_obj.data(results)["targets"] if t["name"] == eyes.Name), {})
    traced = next(t for t in results_obj.traced(results)["targets"] if t["name"] == eyes.Name)
    STATUS["max_ugr_traced"], STATUS["max_ugr_shown"] = traced.get("ugr"), grid.get("ugr")
    expect(grid.get("ugr") is not None and traced.get("ugr") is not None
           and grid["ugr"] != traced["ugr"], f"the eye grid's UGR did not follow the scene: "
           f"{traced.get('ugr')} -> {grid.get('ugr')}")
    panel.sections["scenes"].ensurePolished()
    panel.scroll.ensureWidgetVisible(panel.sections["scenes"])
    pump(0.5)
    grab_window("light_scenes", docs_name="light-scenes.png")
    view.combo.setCurrentIndex(0)  # As traced
    pump(0.5)
    expect(abs(_em(panel, "Workplane") - full) < 0.6,
           f"As traced shows {_em(panel, 'Workplane')} instead of {full}")


scenario(body)
