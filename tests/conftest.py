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
