"""The configuration is read again while the editor runs: the server registers file watchers for
`mcc.toml` and `pyproject.toml` (dynamic registration, where the client supports it) and, when one
changes, analyses the open documents again and publishes their diagnostics."""

from __future__ import annotations

import asyncio

import pytest
from lsprotocol import types as t

from lsp_client import client, fixture_text  # noqa: F401 (client is the fixture)
from test_features import EXPECTED, OpenAt, codes

pytestmark = pytest.mark.asyncio(loop_scope="module")


async def test_the_server_registers_watchers_for_the_configuration_files(client):
    for _ in range(100):
        if client.registrations:
            break
        await asyncio.sleep(0.02)
    [registration] = [r for r in client.registrations if r.method == t.WORKSPACE_DID_CHANGE_WATCHED_FILES]
    options = registration.register_options
    patterns = {w["globPattern"] if isinstance(w, dict) else w.glob_pattern
                for w in (options["watchers"] if isinstance(options, dict) else options.watchers)}
    assert patterns == {"**/mcc.toml", "**/pyproject.toml"}


async def published(client, uri: str, expected: set[str]) -> set[str]:
    for _ in range(200):
        if codes(client.diagnostics.get(uri, [])) == expected:
            break
        await asyncio.sleep(0.05)
    return codes(client.diagnostics.get(uri, []))


async def test_editing_tool_mcc_in_pyproject_changes_the_diagnostics(client, tmp_path):
    pyproject = tmp_path / "pyproject.toml"
    pyproject.write_text('[project]\nname = "cell"\n\n[tool.mcc]\nignore = ["M3"]\n')
    doc = OpenAt(client, tmp_path / "feeder.mxt", fixture_text("mcode"))
    assert codes(await doc.settled()) == set()
    pyproject.write_text('[project]\nname = "cell"\n\n[tool.mcc]\nignore = ["M306"]\n')
    client.workspace_did_change_watched_files(t.DidChangeWatchedFilesParams(
        changes=[t.FileEvent(uri=pyproject.as_uri(), type=t.FileChangeType.Changed)]))
    assert await published(client, doc.uri, EXPECTED["mcode"] - {"M306"}) == EXPECTED["mcode"] - {"M306"}


async def test_a_configuration_file_created_next_to_the_program_applies(client, tmp_path):
    folder = tmp_path / "cell"
    folder.mkdir()
    doc = OpenAt(client, folder / "feeder.mxt", fixture_text("mcode"))
    assert codes(await doc.settled()) == EXPECTED["mcode"]
    config = folder / "mcc.toml"
    config.write_text('ignore = ["M301"]\n')
    client.workspace_did_change_watched_files(t.DidChangeWatchedFilesParams(
        changes=[t.FileEvent(uri=config.as_uri(), type=t.FileChangeType.Created)]))
    assert await published(client, doc.uri, EXPECTED["mcode"] - {"M301"}) == EXPECTED["mcode"] - {"M301"}
    config.unlink()
    client.workspace_did_change_watched_files(t.DidChangeWatchedFilesParams(
        changes=[t.FileEvent(uri=config.as_uri(), type=t.FileChangeType.Deleted)]))
    assert await published(client, doc.uri, EXPECTED["mcode"]) == EXPECTED["mcode"]


async def test_without_watchers_the_next_edit_reads_the_configuration_again(client, tmp_path):
    """Editors without file watchers (Neovim before 0.10, Helix) never report a changed file: the
    server looks at the configuration files' times and sizes at every edit."""
    folder = tmp_path / "quiet"
    folder.mkdir()
    config = folder / "mcc.toml"
    config.write_text('ignore = ["M3"]\n')
    doc = OpenAt(client, folder / "feeder.mxt", fixture_text("mcode"))
    assert codes(await doc.settled()) == set()
    config.write_text('ignore = ["M306", "M309"]\n')  # no notification
    doc.edit(0, 0, 0, " ")
    assert await published(client, doc.uri, EXPECTED["mcode"] - {"M306", "M309"}) == \
        EXPECTED["mcode"] - {"M306", "M309"}
