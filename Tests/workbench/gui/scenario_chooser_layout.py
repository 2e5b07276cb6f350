"""GUI scenario: a luminaire layout is first-class in the chooser and the property editor.
From the Start page: the office model without its four luminaires, a 3 x 2 layout of area
panels on the ceiling. The user selects the layout (as clicking any of its luminaires in the
3D view does), opens "Choose luminaire data": the panel names the layout and its six
luminaires, not "No luminaire selected". Assign gives the file to the layout's template in
one undo step and creates no stray luminaire; the layout itself now shows the file, the
file's flux and the MF, and editing its flux and MF in the property editor changes the
template (every member); undo takes each step back."""
import os

from guilib import STATUS, expect, grab_window, log, office_without_luminaires, pump, scenario, \
    wait_until

def _office_with_layout():
    """The office without its luminaires, plus a 3 x 2 layout over the ceiling's underside."""
    import FreeCAD
    import FreeCADGui

    import lighting

    doc, office_model = office_without_luminaires()
    ceiling = doc.getObject(office_model.OBJECTS["ceiling"])
    face = office_model.find_face(ceiling.Shape, FreeCAD.Vector(0, 0, -1),
                                  FreeCAD.Vector(0, 0, 3000))
    doc.openTransaction("Luminaire layout")
    layout = lighting.add_luminaire_layout(doc, ceiling, face, rows=2, columns=3,
                                           flux_lm=3000.0, maintenance_factor=0.8)
    doc.commitTransaction()
    doc.recompute()
    ceiling.ViewObject.Transparency = 80
    doc.getObject(office_model.OBJECTS["walls"]).ViewObject.Transparency = 60
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    pump(0.5)
    return doc, layout


def _edit_in_property_editor(doc, layout, template):
    """Flux and MF typed on the layout reach the template; each edit undoes on its own."""
    for prop, value in (("FluxLumen", 2500.0), ("MaintenanceFactor", 0.7)):
        doc.openTransaction(f"Edit {prop}")
        setattr(layout, prop, value)
        doc.commitTransaction()
        doc.recompute()
        pump(0.2)
        expect(getattr(template, prop) == value,
               f"layout {prop} {value} did not reach the template ({getattr(template, prop)})")
    STATUS["after_edit"] = [template.FluxLumen, template.MaintenanceFactor]
    doc.undo()
    doc.recompute()
    pump(0.2)
    expect(template.MaintenanceFactor == 0.8 and layout.MaintenanceFactor == 0.8,
           f"undo of the MF edit: template {template.MaintenanceFactor}, "
           f"layout {layout.MaintenanceFactor}")
    expect(template.FluxLumen == 2500.0, f"undo took back too much: {template.FluxLumen}")


def body() -> None:
    import FreeCADGui

    doc, layout = _office_with_layout()
    template = layout.Template
    expect(layout.FluxLumen == 3000.0 and layout.MaintenanceFactor == 0.8,
           f"layout shows flux {layout.FluxLumen}, MF {layout.MaintenanceFactor}")
    for prop in ("PhotometricFile", "FluxLumen", "MaintenanceFactor"):
        expect(layout.getGroupOfProperty(prop) == "Luminaire type" and
               layout.getEditorMode(prop) == [], f"{prop} not editable on the layout")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(layout)
    FreeCADGui.runCommand("Lighting_ChooseLuminaire")
    from lighting.taskpanels import luminaire_chooser

    expect(wait_until(lambda: luminaire_chooser.last_panel() is not None
                      and FreeCADGui.Control.activeDialog(), 5.0), "the chooser did not open")
    panel = luminaire_chooser.last_panel()
    pump(0.5)
    targets = panel.targets.text()
    STATUS["targets"] = targets
    expect("No luminaire selected" not in targets and layout.Label in targets
           and "all 6 luminaires" in targets, f"targets: {targets!r}")
    entry = panel.select("downlight.ies")
    pump(0.3)
    before, steps = len(doc.Objects), list(doc.UndoNames)
    panel.button_box.button(panel.button_box.Apply).click()
    pump(0.5)
    STATUS["status_line"] = panel.status.text()
    grab_window("chooser_layout", docs_name="chooser-layout.png")
    expect(len(doc.Objects) == before, f"Assign made {len(doc.Objects) - before} new objects")
    expect(list(doc.UndoNames)[:1] == ["Assign luminaire data"] and
           len(doc.UndoNames) == len(steps) + 1, f"undo steps {list(doc.UndoNames)[:3]}")
    real = os.path.realpath(entry.path)
    STATUS["after_assign"] = [template.LuminaireType, template.FluxLumen, layout.FluxLumen,
                              layout.PhotometricFile]
    expect(template.LuminaireType == "Photometric" and
           os.path.realpath(template.PhotometricFile) == real, "the template did not change")
    expect(os.path.realpath(layout.PhotometricFile) == real and layout.FluxLumen == 1500.0,
           f"the layout shows {layout.PhotometricFile!r}, {layout.FluxLumen} lm")
    panel.reject()
    pump(0.3)
    _edit_in_property_editor(doc, layout, template)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(layout)
    pump(0.5)
    grab_window("layout_properties")
    doc.undo()  # the flux edit
    doc.undo()  # the assign
    doc.recompute()
    pump(0.3)
    expect(template.LuminaireType == "Area" and template.FluxLumen == 3000.0
           and layout.FluxLumen == 3000.0 and layout.PhotometricFile == "",
           f"undo of the assign: {template.LuminaireType} {template.FluxLumen} "
           f"layout {layout.FluxLumen} {layout.PhotometricFile!r}")
    log("chooser layout scenario done")


scenario(body)
