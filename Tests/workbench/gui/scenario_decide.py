"""GUI scenario: "undecided" says what to do, and two runs keep the same colour scale. The user
builds the office, types a required Em just under what the workplane gets (572 lx), and runs
with a small photon budget: the workplane's Em is undecided, and the panel's Undecided section
says what deciding costs (photons, seconds) with a Decide button. One click runs again and
decides it. (The automatic continuation is limited to 1 ms here, so the panel says why the
run stopped: what deciding needs, more than that limit.) The facts say the photons traced and
the time it took (never "0.00 s"), and the legend keeps the scale set from the requirements
(locked) over both runs."""
import os
import sys

from guilib import STATUS, expect, grab_window, log, pump, scenario, wait_until

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))


def wait_for_run(panel_module, job_before=None, timeout_s: float = 120.0):
    ok = wait_until(lambda: panel_module.last_run() is not None
                    and panel_module.last_run() is not job_before
                    and panel_module.last_run().finished, timeout_s)
    expect(ok, "the run did not finish")
    pump(0.5)
    return panel_module.last_run()


def show_section(panel, name: str) -> None:
    """Scroll the panel so the section is in view, as a user scrolls to it."""
    panel.scroll.ensureWidgetVisible(panel.sections[name])
    pump(0.3)


def body() -> None:
    import FreeCADGui

    import office_model
    from lighting.taskpanels import analysis_panel

    import FreeCAD

    # A user who keeps runs short: a decide run goes on by itself for at most 1 ms of tracing
    # (the preference; default 30 s, which would decide this one without asking).
    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/Lighting").SetFloat(
        "DecideLimitSeconds", 0.001)
    # Seed 6: 572 lx lies inside the first 16384 photons' interval (576.1 [569.2, 582.9] lx)
    # under next-event estimation, the default; seed 1's (583.5 +- 7) would decide it at once
    # (Tests/workbench/test_decide.py, SEED).
    doc = office_model.build_office(photons=16384, seed=6)
    office_model.show_in_gui(doc)
    pump(0.5)
    workplane = [o for o in doc.Objects if o.Label == "Workplane"][0]
    workplane.RequiredLux = 572.0  # the property editor's value, as a user types it
    doc.recompute()
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    expect(analysis.ScaleMode == "Requirements", f"a new analysis' scale: {analysis.ScaleMode}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Run")
    first = wait_for_run(analysis_panel)
    panel = analysis_panel.last_panel()
    view = panel.decide_view
    STATUS["undecided"] = [item.text() for item in view.items]
    log(f"undecided: {STATUS['undecided']}; facts: {panel.facts.text()}")
    expect(any(i.target == "Workplane" and i.name == "Em" for i in view.items),
           f"the workplane's Em is not listed as undecided: {STATUS['undecided']}")
    expect(len(view.buttons) >= 1, "no Decide button")
    expect(all("photons" in i.text() for i in view.items), "a row does not say the photons")
    why = view.summary.text()
    STATUS["why_not"] = why
    expect("The run did not decide them: deciding needs up to" in why
           and "more than the 0.001 s a run continues by itself" in why,
           f"the panel does not say why the run did not decide: {why}")
    expect("0.00 s" not in panel.facts.text(), f"facts: {panel.facts.text()}")
    expect("every requirement decided" not in panel.facts.text(),
           f"the facts say decided with an undecided row: {panel.facts.text()}")
    scale_before = (panel.legend.scale.min_lux, panel.legend.scale.max_lux)
    lock_text = panel.display_view.lock.text()
    expect(lock_text.startswith("Locked"), f"the scale is not locked: {lock_text}")
    show_section(panel, "undecided")
    grab_window("decide_before", docs_name="decide-undecided.png")
    if not view.buttons:
        return
    budget = int(view.buttons[0].text().split("(")[1].split(" photons")[0].replace("\u202f", ""))
    view.buttons[0].click()  # the one click
    second = wait_for_run(analysis_panel, first)
    expect(second is not first, "Decide started no run")
    pump(0.5)
    facts, status = panel.facts.text(), panel.status.text()
    STATUS.update(facts=facts, status=status, budget=budget, photons=int(analysis.Photons),
                  scale=[scale_before, (panel.legend.scale.min_lux, panel.legend.scale.max_lux)])
    log(f"after Decide: {facts} | {status}")
    expect(int(analysis.Photons) == budget and bool(analysis.Decide),
           f"Decide did not run with its budget: Photons {analysis.Photons}, budget {budget}")
    expect(not view.items, f"still undecided after Decide: {[i.text() for i in view.items]}")
    expect("every requirement decided" in facts, f"facts: {facts}")
    expect("photons traced" in status and "run took" in status and "0.00 s" not in status,
           f"status: {status}")
    traced = int(second.data["photons"]) if second.data else -1
    expect(0 < traced <= budget, f"traced {traced} photons of a budget of {budget}")
    expect((panel.legend.scale.min_lux, panel.legend.scale.max_lux) == scale_before,
           f"the colour scale changed between runs: {STATUS['scale']}")
    expect(scale_before == (0.0, 1000.0), f"scale {scale_before}: not 0 to 1.5 x 572 lx rounded")
    show_section(panel, "results")
    grab_window("decide_after")
    show_section(panel, "display")
    grab_window("decide_scale")


scenario(body)
