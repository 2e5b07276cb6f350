"""Inside freecadcmd: run one test module with unittest and return an exit status.

0 = passed, 1 = failed or errored, 77 = every test was skipped (with the reasons printed)."""
import importlib
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def main(suite: str, args: list) -> int:
    for path in (HERE, os.path.join(REPO, "Examples")):
        if path not in sys.path:
            sys.path.insert(0, path)
    import lighting  # noqa: F401 - must come from the installed Mod/Lighting

    print(f"fc_runner: lighting {lighting.__version__} from {lighting.__file__}", flush=True)
    module = importlib.import_module(f"test_{suite}")
    loader = unittest.TestLoader()
    if args:
        tests = unittest.TestSuite(loader.loadTestsFromName(name, module) for name in args)
    else:
        tests = loader.loadTestsFromModule(module)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(tests)
    sys.stdout.flush()
    if not result.wasSuccessful():
        return 1
    if result.testsRun and len(result.skipped) == result.testsRun:
        for test, reason in result.skipped:
            print(f"fc_runner: SKIPPED {test.id()}: {reason}")
        return 77
    return 0
