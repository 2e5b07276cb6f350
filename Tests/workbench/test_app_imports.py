"""App code never imports GUI code (issue 11, item 5).

The workbench follows FEM's layout: App modules (objects, solver, export, api, geometry...)
run headless; the GUI packages (view providers, task panels, commands) may import App code
but never the other way round. Colours come from view providers (``updateData``) and a
GUI-side document observer (lighting/viewproviders/observer.py).

Three checks, each naming the offending import chain:
- every App module, found by walking the package, imports with the GUI modules unimportable;
- no App source file imports a GUI module anywhere, inside functions included (an import
  behind ``if FreeCAD.GuiUp:`` is still App code importing GUI code);
- a whole headless workflow (objects, display settings, analyze, clear, save + reopen) run
  with ``FreeCAD.GuiUp`` pretended true imports none.
The guard and the scanner are tested on planted violations, so the checks can fail."""
from __future__ import annotations

import ast
import builtins
import importlib
import importlib.util
import json
import os
import subprocess
import sys
import unittest
from typing import Any, Iterable, List, Optional

import FreeCAD

import lighting
from wbtest import HERE, DocTestCase, needs_solver, work_dir

PACKAGE = "lighting"
#: The GUI packages of the workbench; every other module of the package is App code.
GUI_PACKAGES = ("lighting.viewproviders", "lighting.taskpanels", "lighting.commands")
#: Third-party GUI modules App code must not import.
GUI_MODULES = ("FreeCADGui", "PySide", "PySide2", "PySide6", "shiboken2", "shiboken6", "pivy")


def _under(name: str, roots: Iterable[str]) -> bool:
    return any(name == root or name.startswith(root + ".") for root in roots)


def is_gui(name: str) -> bool:
    """True for a GUI module: a GUI package of the workbench or a Qt/Coin/FreeCADGui module."""
    return _under(name, GUI_PACKAGES) or _under(name, GUI_MODULES)


def is_app(name: str) -> bool:
    """True for an App module of the workbench."""
    return _under(name, (PACKAGE,)) and not _under(name, GUI_PACKAGES)


def package_root() -> str:
    return os.path.dirname(os.path.abspath(lighting.__file__))


def app_modules() -> List[tuple]:
    """(module name, file) of every App module, found by walking the package's folders."""
    root = package_root()
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if os.path.isfile(os.path.join(folder, d, "__init__.py")))
        package = os.path.relpath(folder, os.path.dirname(root)).replace(os.sep, ".")
        for name in sorted(files):
            if name.endswith(".py"):
                module = package if name == "__init__.py" else f"{package}.{name[:-3]}"
                if is_app(module):
                    found.append((module, os.path.join(folder, name)))
    return found


def _chain(frame: Any) -> str:
    """The workbench frames (outermost first) that led to an import."""
    steps = []
    while frame is not None:
        name = frame.f_globals.get("__name__", "")
        if _under(name, (PACKAGE,)) or name.startswith("test_"):
            where = frame.f_code.co_name
            where = "module level" if where == "<module>" else f"in {where}()"
            steps.append(f"{name}:{frame.f_lineno} ({where})")
        frame = frame.f_back
    return " -> ".join(reversed(steps))


def _importer_frame() -> Optional[Any]:
    """The frame that executes the import statement (importlib's own frames skipped)."""
    frame = sys._getframe(2)
    while frame is not None and ("importlib" in frame.f_code.co_filename or
                                 frame.f_code.co_filename == __file__):
        frame = frame.f_back
    return frame


class GuiImportGuard:
    """While active, an App module importing a GUI module is recorded (with its import
    chain) and gets an ImportError; the GUI packages of the workbench are unimportable.

    A meta path finder sees imports of modules not loaded yet (``importlib.import_module``
    too); a ``builtins.__import__`` wrapper sees import statements of modules already loaded
    (FreeCAD's Arch loads PySide headless). Third-party modules may import Qt: only the
    workbench's App modules are held to the rule."""

    def __init__(self, purge: bool = False) -> None:
        self.purge = purge
        self.violations: List[str] = []
        self._saved: dict = {}
        self._import = builtins.__import__

    # -- meta path finder --------------------------------------------------------------
    def find_spec(self, name: str, path: Any = None, target: Any = None) -> None:
        if not is_gui(name):
            return None
        frame = _importer_frame()
        importer = frame.f_globals.get("__name__", "") if frame is not None else ""
        if _under(name, GUI_PACKAGES) or is_app(importer):
            self._refuse(name, frame)
        return None

    # -- builtins.__import__ -----------------------------------------------------------
    def _guarded_import(self, name: str, globals: Any = None, locals: Any = None,
                        fromlist: Any = (), level: int = 0) -> Any:
        importer = (globals or {}).get("__name__", "")
        if is_app(importer):
            module = name
            if level:
                module = importlib.util.resolve_name("." * level + name,
                                                     globals.get("__package__") or importer)
            wanted = [module] + [f"{module}.{item}" for item in (fromlist or ()) if item != "*"]
            refused = [w for w in wanted if is_gui(w)]
            if refused:
                self._refuse(max(refused, key=len), sys._getframe(1))
        return self._import(name, globals, locals, fromlist, level)

    def _refuse(self, name: str, frame: Any) -> None:
        chain = f"{_chain(frame)} -> imports {name}"
        if chain not in self.violations:
            self.violations.append(chain)
        raise ImportError(f"App code imports the GUI module {name}: {chain}")

    # -- context manager ---------------------------------------------------------------
    def __enter__(self) -> "GuiImportGuard":
        if self.purge:  # import every workbench and GUI module afresh (fresh process only)
            for name in list(sys.modules):
                if _under(name, (PACKAGE,)) or is_gui(name):
                    self._saved[name] = sys.modules.pop(name)
        sys.meta_path.insert(0, self)
        builtins.__import__ = self._guarded_import
        return self

    def __exit__(self, *exc: Any) -> None:
        builtins.__import__ = self._import
        sys.meta_path.remove(self)
        for name, module in self._saved.items():
            sys.modules.setdefault(name, module)


def gui_imports_in_source(path: str, module: str) -> List[str]:
    """Every import of a GUI module in a source file, wherever it stands: ``file:line``."""
    with open(path, encoding="utf-8") as stream:
        tree = ast.parse(stream.read(), path)
    package = module if path.endswith("__init__.py") else module.rpartition(".")[0]
    found = []

    def report(node: ast.AST, names: List[str]) -> None:
        gui = [name for name in names if is_gui(name)]
        if gui:  # one line per import, naming its most specific GUI module
            found.append(f"{os.path.relpath(path, os.path.dirname(package_root()))}:"
                         f"{node.lineno}: {module} imports {max(gui, key=len)}")

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                report(node, [alias.name])
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = importlib.util.resolve_name("." * node.level + base, package)
            report(node, [base] + [f"{base}.{alias.name}" for alias in node.names])
        elif isinstance(node, ast.Call) and node.args:
            func = node.func
            called = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
            if called in ("import_module", "__import__"):
                report(node, [_literal_prefix(node.args[0]).rstrip(".")])
    return sorted(found, key=lambda line: (line.split(":")[0], int(line.split(":")[1])))


def _literal_prefix(node: ast.AST) -> str:
    """The constant start of a string argument ("lighting.viewproviders." of an f-string)."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr) and node.values and isinstance(node.values[0], ast.Constant):
        return str(node.values[0].value)
    return ""


CHILD = """
import json, sys
sys.path.insert(0, {here!r})
import test_app_imports
with open({out!r}, "w", encoding="utf-8") as stream:
    json.dump(test_app_imports.import_app_modules(), stream)
sys.exit(0)
"""


def import_app_modules() -> dict:
    """Import every App module afresh under the guard (run in a child freecadcmd, whose
    modules it replaces): {"modules", "violations", "errors"}."""
    modules = [name for name, _ in app_modules()]
    errors = []
    with GuiImportGuard(purge=True) as guard:
        for name in modules:
            try:
                importlib.import_module(name)
            except ImportError as exc:
                errors.append(f"{name}: {exc}")
    return {"modules": modules, "violations": guard.violations, "errors": errors}


def _fail_on(title: str, problems: List[str]) -> None:
    if problems:
        raise AssertionError(f"{title}:\n" + "\n".join(problems))


class GuardSelfTest(unittest.TestCase):
    """The guard and the scanner catch planted violations (so the real checks can fail)."""

    def _run_as(self, module_name: str, source: str) -> GuiImportGuard:
        with GuiImportGuard() as guard:
            try:
                exec(compile(source, f"<{module_name}>", "exec"), {"__name__": module_name})
            except ImportError:
                pass
        return guard

    def test_guard_refuses_gui_imports_from_app_code(self):
        for source, name in (("from lighting.viewproviders import coloring", "coloring"),
                             ("import lighting.taskpanels.analysis_panel", "analysis_panel"),
                             ("from PySide import QtCore", "PySide"),
                             ("import FreeCADGui", "FreeCADGui"),
                             ("import importlib\nimportlib.import_module("
                              "'lighting.commands.commands')", "commands")):
            guard = self._run_as("lighting.objects._planted", source)
            self.assertEqual(len(guard.violations), 1, source)
            self.assertIn("lighting.objects._planted", guard.violations[0])
            self.assertIn(name, guard.violations[0])

    def test_guard_lets_app_and_gui_code_import_app_code(self):
        self.assertEqual(self._run_as("lighting.solver._planted",
                                      "import json\nfrom lighting import units").violations, [])
        self.assertEqual(self._run_as("lighting.viewproviders._planted",
                                      "from lighting.objects import base").violations, [])

    def test_scanner_finds_imports_inside_functions(self):
        path = os.path.join(work_dir("scan"), "planted.py")
        with open(path, "w", encoding="utf-8") as stream:
            stream.write("import FreeCAD\n\ndef refresh(obj):\n    if FreeCAD.GuiUp:\n"
                         "        from lighting.viewproviders import coloring\n"
                         "        coloring.refresh(obj)\n\n"
                         "def attach(kind):\n    import importlib\n"
                         "    return importlib.import_module(f'lighting.viewproviders.{kind}')\n")
        found = gui_imports_in_source(path, "lighting.objects.planted")
        self.assertEqual(len(found), 2, found)  # the function's import, import_module
        self.assertTrue(all("lighting.objects.planted imports lighting.viewproviders" in f
                            for f in found), found)


class AppImports(DocTestCase):
    def test_walk_finds_the_app_modules(self):
        names = [name for name, _ in app_modules()]
        for expected in ("lighting", "lighting.api", "lighting.objects.analysis",
                         "lighting.objects.factory", "lighting.solver.store",
                         "lighting.export.scene"):
            self.assertIn(expected, names)
        self.assertFalse([n for n in names if is_gui(n)])
        for package in GUI_PACKAGES:  # the explicit list names real packages
            folder = os.path.join(os.path.dirname(package_root()), *package.split("."))
            self.assertTrue(os.path.isfile(os.path.join(folder, "__init__.py")), package)

    def test_every_app_module_imports_without_gui(self):
        """In a fresh freecadcmd: import every App module with the GUI modules unimportable."""
        out = os.path.join(work_dir("imports"), "imports.json")
        code = CHILD.format(here=HERE, out=out)
        proc = subprocess.run([os.environ.get("FREECADCMD", "freecadcmd"), "-c", code],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stdout[-3000:] + proc.stderr[-3000:])
        with open(out, encoding="utf-8") as stream:
            report = json.load(stream)
        self.assertEqual(report["modules"], [name for name, _ in app_modules()])
        _fail_on("App modules import GUI modules", report["violations"])
        self.assertEqual(report["errors"], [])
        print(f"\n{len(report['modules'])} App modules imported without GUI modules")

    def test_no_app_source_imports_gui(self):
        found = []
        for name, path in app_modules():
            found.extend(gui_imports_in_source(path, name))
        _fail_on("App code imports GUI code", found)

    @needs_solver
    def test_headless_workflow_with_gui_up_imports_no_gui(self):
        """Objects, display settings, analyze, clear, save and reopen with GuiUp pretended
        true: App code behaves the same whether or not a GUI exists."""
        doc = FreeCAD.newDocument("NoGui")
        floor = doc.addObject("Part::Box", "Floor")
        floor.Length, floor.Width, floor.Height = 4000, 3000, 10
        doc.recompute()
        path = os.path.join(work_dir("nogui"), "nogui.FCStd")
        guard, was_up = GuiImportGuard(), FreeCAD.GuiUp
        FreeCAD.GuiUp = True
        try:
            with guard:
                analysis = lighting.make_analysis(doc, photons=20000)
                lighting.make_luminaire(doc, (2.0, 1.5, 2.5), kind="Point", flux_lm=1000.0)
                lighting.make_grid_target(doc, floor, height_m=0.0, spacing_m=1.0)
                doc.recompute()
                analysis.ColorMap, analysis.ScaleMode, analysis.ShowLegend = "Heat", "Fixed", False
                result = lighting.analyze(doc, output_dir=work_dir("nogui-out"))
                from lighting.solver import store

                store.clear(analysis)
                lighting.analyze(doc, output_dir=work_dir("nogui-out2"))
                doc.saveAs(path)
                FreeCAD.closeDocument(doc.Name)
                doc = FreeCAD.openDocument(path)
                reopened = lighting.results(doc)
        except ImportError:
            self.assertTrue(guard.violations)  # reported below
        finally:
            FreeCAD.GuiUp = was_up
        _fail_on("App code imports GUI modules", guard.violations)
        self.assertGreater(result["Workplane"].mean_lux, 0.0)
        from lighting.objects import results as results_obj

        stored = results_obj.of_analysis(doc.getObject("LightingAnalysis"))
        self.assertEqual(reopened["Workplane"].mean_lux, results_obj.mean_lux(stored, "Workplane"))

if __name__ == "__main__":
    unittest.main()
