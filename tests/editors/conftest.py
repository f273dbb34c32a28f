"""Keeps each test's outcome on its item, so that a failing editor test can leave a screenshot and
the extension's log behind (test_vscode_codeserver.py's `editor` fixture)."""

from __future__ import annotations

import pytest


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.when == "call":
        item.call_report = report
