"""GUI scenario: what a first-hour user sees at 1280 x 1024. The main window fills the screen;
the example office is built and analysed from the toolbar. The main
commands (Run analysis, Live results, Optimize placement, Results, Report, Clear results) are
buttons on screen, not behind a toolbar's overflow arrow; the legend's title lines end left of
the navigation cube (top-right corner). Then the analysed document is saved, closed and
reopened: it does not show as modified. (The office is built as Examples/office.py builds it,
in a document with one 3D view, so that the screenshot shows the view.)"""
import os

from guilib import (OUT, STATUS, expect, main_window, pump, run_from_toolbar, scenario,
                    visible_in_window)

REPO = os.environ.get("LIGHTING_SOURCE_DIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
MAIN_COMMANDS = ("Lighting_Run", "Lighting_Live", "Lighting_Optimize", "Lighting_Results",
                 "Lighting_Report", "Lighting_ClearResults")


def on_screen(widget) -> bool:
    """The widget lies inside the 1280 x 1024 screen (a window wider than the screen would
    let a button count as shown while the user cannot see it)."""
    from PySide import QtCore, QtGui

    screen = QtGui.QApplication.desktop().screenGeometry()
    top_left = widget.mapToGlobal(QtCore.QPoint(0, 0))
    return screen.contains(QtCore.QRect(top_left, widget.size()))


def check_toolbar() -> None:
    """Each main command has a visible, whole button in the window."""
    import FreeCADGui
    from PySide import QtGui

    shown = {}
    for name in MAIN_COMMANDS:
        text = FreeCADGui.Command.get(name).getInfo()["menuText"].replace("&", "")
        button = None
        for bar in main_window().findChildren(QtGui.QToolBar):
            for action in bar.actions():
                if action.text().replace("&", "") == text and bar.isVisible():
                    button = bar.widgetForAction(action)
        shown[text] = button is not None and visible_in_window(button) and on_screen(button)
    STATUS["main_commands_shown"] = shown
    STATUS["window_after_run"] = [main_window().width(), main_window().height()]
    expect(all(shown.values()), f"main commands behind the overflow at 1280 px: {shown}")


def check_legend_clear_of_cube() -> None:
    """Every legend title line, drawn from the left edge, ends before the navigation cube."""
    import FreeCAD
    from PySide import QtGui

    from lighting.viewproviders import analysis as vp

    view = main_window().findChild(QtGui.QMdiArea).activeSubWindow().widget()
    params = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/View")
    cube = params.GetInt("CubeSize", 132) if params.GetBool("ShowNaviCube", True) else 0
    corner = params.GetInt("CornerNaviCube", 1)  # 0 top left, 1 top right
    analysis = FreeCAD.ActiveDocument.getObject("LightingAnalysis")
    proxy = analysis.ViewObject.Proxy
    lines = vp.title_lines(vp.STALE_TITLE if proxy.results_stale() else proxy.legend_title())
    lines += vp.title_lines(vp.STALE_TITLE)  # the longest title it can show
    font = QtGui.QFont()
    font.setPixelSize(14)  # the legend's SoFont size
    metrics = QtGui.QFontMetrics(font)
    left = (vp.X0 + 1.0) / 2.0 * view.width()
    widest = max(metrics.boundingRect(line).width() for line in lines)
    right = left + 1.25 * widest  # a margin for Coin's own font
    STATUS["legend"] = {"lines": lines, "right_px": right, "view_px": view.width(),
                        "cube_px": cube, "corner": corner}
    expect(corner == 1 and right < view.width() - cube - 10,
           f"legend title reaches the navigation cube: {STATUS['legend']}")


def check_reopen_unmodified(path: str) -> None:
    import FreeCAD
    import FreeCADGui

    doc = FreeCAD.ActiveDocument
    STATUS["touched_before_save"] = [o.Name for o in doc.Objects if "Touched" in o.State]
    doc.save()
    pump(0.3)
    name = doc.Name
    FreeCAD.closeDocument(name)
    pump(0.5)

    class Changes:  # which properties change while the file opens (when it fails: why)
        seen: list = []

        def slotChangedObject(self, obj, prop):  # noqa: N802 (FreeCAD API name)
            if not getattr(obj.Document, "Restoring", False):
                self.seen.append(f"{obj.Name}.{prop}")

    changes = Changes()
    FreeCAD.addDocumentObserver(changes)
    try:
        again = FreeCAD.openDocument(path)
        pump(1.5)
    finally:
        FreeCAD.removeDocumentObserver(changes)
    touched = [o.Name for o in again.Objects if "Touched" in o.State]
    modified = FreeCADGui.getDocument(again.Name).Modified
    STATUS["reopened"] = {"modified": modified, "touched": touched,
                          "changed": sorted(set(changes.seen))}
    expect(not modified and not touched, f"the reopened document shows as modified: {touched}")


def build_office(path: str):
    """The example office in a new document with one 3D view, saved to ``path`` (as the
    example does), shown as the example shows it."""
    import sys

    import FreeCAD

    sys.path.insert(0, os.path.join(REPO, "Examples"))
    import office_model

    STATUS["documents_at_start"] = sorted(FreeCAD.listDocuments())
    doc = FreeCAD.newDocument("office")
    pump(0.3)
    STATUS["documents_after_new"] = sorted(FreeCAD.listDocuments())
    office_model.build_office(doc, photons=20000)
    STATUS["documents_after_build"] = sorted(FreeCAD.listDocuments())
    expect(STATUS["documents_after_build"] == [doc.Name],
           f"other documents open after building: {STATUS['documents_after_build']}")
    office_model.show_in_gui(doc)
    doc.saveAs(path)
    pump(0.5)
    return doc


def grab_with_view(name: str, docs_name: str) -> str:
    """guilib.grab_window, painting the active 3D view (guilib paints one only when exactly
    one 3D view is shown; building right after the Start page can leave two)."""
    import tempfile

    import FreeCAD
    import FreeCADGui
    from PySide import QtCore, QtGui

    window = main_window()
    area = window.findChild(QtGui.QMdiArea)
    widget = area.activeSubWindow().widget()
    STATUS["views_3d"] = [FreeCAD.listDocuments().keys().__len__(), len(area.subWindowList())]
    pump(0.3)
    picture = window.grab()
    with tempfile.TemporaryDirectory() as folder:
        image = os.path.join(folder, "view.png")
        FreeCADGui.activeView().saveImage(image, widget.width(), widget.height(), "Current")
        painter = QtGui.QPainter(picture)
        painter.drawImage(widget.mapTo(window, QtCore.QPoint(0, 0)), QtGui.QImage(image))
        painter.end()
    path = os.path.join(OUT, f"{name}.png")
    picture.save(path)
    STATUS["images"][name] = path
    STATUS["docs_images"][name] = docs_name
    return path


def grab_screen(name: str, docs_name: str = "") -> str:
    """What the X server shows (QScreen.grabWindow(0) reads Xvfb's framebuffer): the 3D view
    as OpenGL drew it, navigation cube included, which a widget grab leaves out."""
    from PySide import QtGui

    pump(0.5)
    path = os.path.join(OUT, f"{name}.png")
    QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(path)
    STATUS["images"][name] = path
    if docs_name:
        STATUS["docs_images"][name] = docs_name
    return path


def measure_title_and_cube(name: str, docs_name: str = "") -> dict:
    """The legend's title and the navigation cube as the X server shows them, with the model
    hidden for a moment (the cube and the legend stay): where the title's dark text ends and
    the cube's light faces begin in the view's top band, in view pixels."""
    import FreeCAD
    from PySide import QtCore, QtGui

    doc = FreeCAD.ActiveDocument
    keep = {"LightingAnalysis"} | {o.Name for o in doc.getObject("LightingAnalysis").Group}
    hidden = [o for o in doc.Objects if o.Name not in keep and o.ViewObject is not None
              and o.ViewObject.Visibility]
    for o in hidden:
        o.ViewObject.Visibility = False
    try:
        path = grab_screen(name, docs_name)
    finally:
        for o in hidden:
            o.ViewObject.Visibility = True
    image = QtGui.QImage(path)
    view = main_window().findChild(QtGui.QMdiArea).activeSubWindow().widget()
    origin = view.mapToGlobal(QtCore.QPoint(0, 0))
    params = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/View")
    cube = params.GetInt("CubeSize", 132)
    width = min(view.width(), image.width() - origin.x())
    dark, cube_left, cube_pixels = {}, None, 0
    for y in range(2, min(cube + 60, view.height())):
        for x in range(2, width - 2):
            colour = QtGui.QColor(image.pixel(origin.x() + x, origin.y() + y))
            r, g, b = colour.red(), colour.green(), colour.blue()
            if max(r, g, b) < 45:  # black text or outlines on the dark blue background
                dark.setdefault(y, []).append(x)
            elif min(r, g, b) > 170 and x > width - cube - 40:  # the cube's light faces
                cube_pixels += 1
                cube_left = x if cube_left is None else min(cube_left, x)
    # The title: rows whose dark pixels start at the left (where the legend is drawn); its
    # right end follows the glyphs while they are less than 30 px apart, so a title running
    # under the cube reaches the cube's own outlines.
    title_right = -1
    for y, xs in dark.items():
        if xs[0] > 0.1 * width:
            continue
        end = xs[0]
        for x in xs[1:]:
            if x - end > 30:
                break
            end = x
        title_right = max(title_right, end)
    return {"title_right_px": title_right, "cube_left_px": cube_left,
            "cube_pixels": cube_pixels, "view_px": width}


def clear_of_cube(found: dict) -> bool:
    return (found["cube_pixels"] > 500 and found["title_right_px"] > 0
            and found["cube_left_px"] is not None
            and found["title_right_px"] < found["cube_left_px"] - 10)


def check_cube_on_screen() -> None:
    """On the real screen the cube is drawn and the title ends left of it; the same
    measurement catches a planted title long enough to run under the cube."""
    import FreeCAD

    from lighting.viewproviders import coloring

    found = measure_title_and_cube("legend_cube_screen", "legend-cube-screen.png")
    STATUS["cube_on_screen"] = found
    expect(found["cube_pixels"] > 500, f"no navigation cube on screen: {found}")
    expect(clear_of_cube(found), f"the legend title reaches the navigation cube: {found}")
    analysis = FreeCAD.ActiveDocument.getObject("LightingAnalysis")
    proxy = analysis.ViewObject.Proxy
    proxy.legend_title = lambda: "Illuminance [lx] with a planted title much too long to " \
                                 "stay clear of the navigation cube in the corner at all"
    try:
        coloring.refresh(analysis)
        planted = measure_title_and_cube("legend_cube_planted")
    finally:
        del proxy.legend_title  # the class' own again
        coloring.refresh(analysis)
    STATUS["cube_planted"] = planted
    expect(not clear_of_cube(planted), f"the pixel check misses a title under the cube: "
                                       f"{planted}")


def body() -> None:
    import FreeCAD

    window = main_window()
    window.move(0, 0)
    window.resize(1280, 1024)
    pump(0.5)
    STATUS["window_size_used"] = [window.width(), window.height()]
    out = os.path.join(OUT, "office.FCStd")
    doc = build_office(out)
    run_from_toolbar(doc)
    pump(0.5)
    expect(not FreeCAD.ActiveDocument.getObject("LightingAnalysis").ViewObject.Proxy
           .results_stale(), "results stale right after the run")
    check_toolbar()
    check_legend_clear_of_cube()
    grab_with_view("toolbar_legend_1280", "toolbar-legend-1280.png")
    grab_screen("toolbar_legend_screen")
    check_reopen_unmodified(out)
    check_cube_on_screen()  # last: it hides the model for a moment (which modifies it)


scenario(body)
