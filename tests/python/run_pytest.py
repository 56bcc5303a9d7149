#!/usr/bin/env python3
"""run_pytest.py: runs one file of tests/python with pytest for CTest (label `python`).

Exit 77, which CTest reports as skipped, with the reason on stdout, when a tool is truly absent
(pytest, NumPy, or the module itself when LANTERN_BUILD_PYTHON was off) or when every test of
the file skipped (no Vulkan device); otherwise pytest's own status.
Usage: run_pytest.py TEST_FILE [--needs-module]
"""
import importlib
import os
import sys

SKIPPED = 77


class Outcomes:
    """Counts what the tests did, and keeps the reasons of the skips."""

    def __init__(self):
        self.passed = self.failed = self.skipped = 0
        self.reasons = []

    def pytest_runtest_logreport(self, report):
        if report.skipped:
            self.skipped += 1
            if isinstance(report.longrepr, tuple):
                self.reasons.append(report.longrepr[2])
        elif report.failed:
            self.failed += 1
        elif report.when == "call":
            self.passed += 1


def main(argv):
    test_file = argv[0]
    needs_module = "--needs-module" in argv
    for module, package in (("pytest", "python3-pytest"), ("numpy", "python3-numpy")):
        try:
            importlib.import_module(module)
        except ImportError:
            print(f"SKIPPED: {module} is not installed (Debian: {package}; "
                  "scripts/install-deps.sh test installs it)")
            return SKIPPED
    if needs_module and os.environ.get("LANTERN_PYTHON_BUILT") != "1":
        print("SKIPPED: the Python module was not built (LANTERN_BUILD_PYTHON is OFF: "
              "python3-dev or pybind11-dev missing, or a sanitizer build)")
        return SKIPPED
    import pytest

    outcomes = Outcomes()
    status = pytest.main(["-q", "-p", "no:cacheprovider", "-rs", test_file], plugins=[outcomes])
    if status == 0 and outcomes.passed == 0 and outcomes.skipped > 0:
        print("SKIPPED: " + "; ".join(sorted(set(outcomes.reasons))))
        return SKIPPED
    return int(status)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
