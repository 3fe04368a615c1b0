"""pytest's set-up for the suite's tests (`make test`: pytest over tests/test_*.py on both cores).

Each test makes many soft checks (helpers.check): all run, each is printed, and the test fails at
its end listing the failed ones. The number of checks passed and failed, over all tests and
workers, is the last line before pytest's own summary."""

import os
import shutil

import pytest

import helpers
from freefem import share_cores

share_cores()


def pytest_configure(config):
    config.addinivalue_line("markers", "heavy(seconds): a test that takes about this long on the 2-core "
                            "machine; the heavy tests start first, longest first")


def pytest_collection_modifyitems(items):
    """The heavy tests first, longest first (the rest in their order): xdist's workers then finish
    together instead of one waiting on a three-minute test that started last (measured: make test's
    pytest 847 s with the long tests where the files put them, ~780 s of work per worker)."""
    def weight(item):
        mark = item.get_closest_marker("heavy")
        return -(mark.kwargs.get("seconds", 60) if mark else 0)
    items.sort(key=weight)


@pytest.hookimpl(hookwrapper=True)
def pytest_pyfunc_call(pyfuncitem):
    helpers.CHECKS.clear()
    outcome = yield
    failed = [c for c in helpers.CHECKS if not c[1]]
    pyfuncitem.user_properties.append(("checks", (len(helpers.CHECKS) - len(failed), len(failed))))
    helpers.CHECKS.clear()
    if failed and outcome.excinfo is None:
        pytest.fail("failed checks:\n" + "\n".join(f"  {name}  {detail}" for name, _, detail in failed), pytrace=False)


def pytest_sessionfinish(session, exitstatus):
    shutil.rmtree(helpers.TMP, ignore_errors=True)


def pytest_terminal_summary(terminalreporter):
    passed = failed = 0
    for reports in terminalreporter.stats.values():
        for report in reports:
            if getattr(report, "when", None) != "call":
                continue
            for key, value in getattr(report, "user_properties", []):
                if key == "checks":
                    passed += value[0]
                    failed += value[1]
    terminalreporter.write_line(f"checks: {passed} passed, {failed} failed")
