"""The language server: pygls 2 wiring of the documents and the feature modules.

Every request answers from the document's latest finished analysis (documents.py) and never
waits for a new one. A request that fails is logged and answered with a JSON-RPC error; the
server itself goes on (pygls turns a handler's exception into an error response, and the
notification handlers here catch and log everything).
"""

from __future__ import annotations

import functools
import gc
import importlib
import logging
import os
import sys
import threading

import attrs
from lsprotocol import types as t
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.uris import to_fs_path

from mcc import __version__
from mcc.lsp import semantic
from mcc.lsp.units import LineText, Units

log = logging.getLogger("mcc.lsp")
CONFIG_NAMES = ("mcc.toml", "pyproject.toml")
REQUEST_FAILED = -32803  # LSP's RequestFailed: the request was valid but cannot be done (a refused rename)
FIX_ALL = "source.fixAll.mcc"  # actions.FIX_ALL, named here so that the capabilities need no import


class Lazy:
    """A module imported when one of its names is first used. The compiler (Lark, the catalogs, the
    IR, the lint rules) takes longer to import than pygls itself: imported when the server starts,
    it held up the answer to `initialize` by a second or more. So `initialize` is answered with only
    pygls loaded, and a thread imports the rest at once after it (`warm_up`), while the editor
    sends its first documents."""

    def __init__(self, name: str, attribute: str | None = None) -> None:
        self._name, self._attribute, self._value = name, attribute, None

    def load(self):
        if self._value is None:
            imported()
            module = importlib.import_module(self._name)
            self._value = getattr(module, self._attribute) if self._attribute else module
        return self._value

    def __getattr__(self, name: str):
        return getattr(self.load(), name)

    def __call__(self, *args, **kwargs):
        return self.load()(*args, **kwargs)


dialects = Lazy("mcc.compiler.dialects")
registry = Lazy("mcc.compiler.codes", "registry")
actions, completion, convert, formatting, hover, lenses, navigation, outline = (
    Lazy(f"mcc.lsp.{name}") for name in
    ("actions", "completion", "convert", "formatting", "hover", "lenses", "navigation", "outline"))
WARM = ("mcc.lsp.documents", "mcc.lsp.analysis", "mcc.lsp.incremental", "mcc.lsp.editor", "mcc.lsp.memory",
        "mcc.compiler.lint.rules", "mcc.lsp.actions", "mcc.lsp.completion", "mcc.lsp.convert", "mcc.lsp.formatting",
        "mcc.lsp.hover", "mcc.lsp.lenses", "mcc.lsp.navigation", "mcc.lsp.outline")


WARMING: list[threading.Thread] = []  # the thread of warm_up, once started


def imported() -> None:
    """Wait for warm_up's imports to finish. Two threads importing the same modules at once can
    meet in a circular import, which Python breaks by failing one of them (_DeadlockError); so the
    protocol thread does not import the compiler itself while warm_up does."""
    for thread in WARMING:
        if thread is not threading.current_thread():
            thread.join()


def warm_up() -> None:
    """Import the compiler and the features (in a thread, after `initialize` was answered)."""
    try:
        for name in WARM:
            importlib.import_module(name)
        from mcc.compiler import dialects as found
        from mcc.lsp.editor import editor_of

        for dialect in found.DIALECTS.values():  # the frontends and their parsers, the editors and indexers
            package = dialect.frontend.rsplit(".", 1)[0]
            dialect.load_frontend()
            importlib.import_module(package + ".parser")
            indexer = editor_of(dialect.name).indexer
            if indexer:
                importlib.import_module(indexer)
    except Exception:  # noqa: BLE001 - what fails here fails again, and is reported, where it is used
        log.exception("importing the compiler failed")


class MccServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("mcc", __version__, text_document_sync_kind=t.TextDocumentSyncKind.Incremental)
        self._documents = None
        self.debounce: float | None = None  # initializationOptions, applied when the documents are made
        self.memory_delay: float | None = None
        self.rules_url: str | None = None
        # documents whose colours or folds were asked for before their first analysis finished:
        # answered empty, so the editor is asked to ask again when it has finished
        self.unanswered: set[str] = set()

    @property
    def documents(self):
        """The open documents and their analyses (made, importing the compiler, at first use)."""
        if self._documents is None:
            imported()
            from mcc.lsp.documents import Documents

            documents = Documents(self.publish, priced=self.refresh_lenses)
            if self.debounce is not None:
                documents.debounce = self.debounce
            if self.memory_delay is not None:
                documents.memory_delay = self.memory_delay
            self._documents = documents
        return self._documents

    def publish(self, snap) -> None:
        diagnostics = [convert.diagnostic(d, snap.source, snap.uri, self.rules_url) for d in snap.diagnostics
                       if d.span.file == snap.path or d.span.file == snap.source.path]
        self.text_document_publish_diagnostics(
            t.PublishDiagnosticsParams(uri=snap.uri, diagnostics=out(snap, diagnostics), version=snap.version))
        if snap.uri in self.unanswered:
            self.unanswered.discard(snap.uri)
            self.refresh(("semantic_tokens", self.workspace_semantic_tokens_refresh),
                         ("folding_range", self.workspace_folding_range_refresh))

    def refresh(self, *requests) -> None:
        """Ask the editor to ask again for what it asked too early, where it supports being asked."""
        workspace = getattr(self.client_capabilities, "workspace", None)
        for name, ask in requests:
            if getattr(getattr(workspace, name, None), "refresh_support", False):
                ask(None)

    def units(self) -> Units:
        """The column unit agreed at `initialize` (UTF-16 before it, as LSP says)."""
        try:
            encoding = self.workspace.position_encoding
        except RuntimeError:  # no workspace yet
            encoding = None
        return Units(str(getattr(encoding, "value", encoding) or "utf-16"))

    def refresh_lenses(self, snap) -> None:
        """A document's program memory is priced or its cycle time run (after a pause in the
        typing): ask the editor to ask again for code lenses, and for inlay hints when there is
        program memory (the hints show nothing else), when it supports being asked."""
        asks = [("code_lens", self.workspace_code_lens_refresh)]
        if snap.memory is not None:
            asks.append(("inlay_hint", self.workspace_inlay_hint_refresh))
        self.refresh(*asks)

    def report_server_error(self, error, source) -> None:  # log; never pop up a message per failure
        log.warning("request failed (%s): %s", getattr(source, "__name__", source), error)

    def snapshot(self, uri: str):
        return self.documents.latest.get(uri)


server = MccServer()


def snapshot_lines(snap) -> LineText:
    """The lines of the text a snapshot was analysed from: its spans' columns are in it."""
    source = snap.source
    return lambda line: source.line_text(line + 1) if 0 <= line < source.line_count else ""


def document_lines(uri: str) -> LineText:
    """The lines of the editor's current text, which the positions of a request are in."""
    lines = server.workspace.get_text_document(uri).lines
    return lambda line: lines[line].rstrip("\r\n") if 0 <= line < len(lines) else ""


def out(snap, result):
    """An answer computed from a snapshot, with its positions in the client's units. In an ASCII
    text every unit counts the same, and nothing is converted (walking the answer for its
    positions cost a third of the time to publish a few hundred diagnostics)."""
    if snap.text.isascii():
        return result
    return server.units().out(result, snapshot_lines(snap))


def character(uri: str, position: t.Position) -> t.Position:
    """A request's position with its column in characters."""
    return server.units().position_from_client(position, document_lines(uri))


def guarded(func):
    """Log a failing handler with its traceback, then let pygls answer with an error."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except JsonRpcException:
            raise
        except Exception as exc:
            if isinstance(exc, navigation.RenameError):
                raise JsonRpcException(str(exc), code=REQUEST_FAILED) from None
            log.exception("%s failed", func.__name__)
            raise

    return wrapper


def quiet(func):
    """Notification handlers: log and swallow, so a bad notification never stops the server."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except Exception:  # noqa: BLE001
            log.exception("%s failed", func.__name__)

    return wrapper


def path_of(uri: str) -> str:
    try:
        return to_fs_path(uri) or uri
    except Exception:  # noqa: BLE001
        return uri


def reader(uri: str):
    def read():
        document = server.workspace.get_text_document(uri)
        return document.source, document.version

    return read


# -- lifecycle and synchronisation -----------------------------------------------------------------

@server.feature(t.INITIALIZE)
@quiet
def initialize(params: t.InitializeParams) -> None:
    options = params.initialization_options if isinstance(params.initialization_options, dict) else {}
    if isinstance(options.get("debounce"), (int, float)):
        server.debounce = max(0.0, float(options["debounce"]) / 1000.0)
    if isinstance(options.get("memoryDelay"), (int, float)):
        server.memory_delay = max(0.0, float(options["memoryDelay"]) / 1000.0)
    if isinstance(options.get("rulesUrl"), str):
        server.rules_url = options["rulesUrl"]
    # the answer goes out now; the compiler is imported meanwhile
    if not WARMING:
        WARMING.append(threading.Thread(target=warm_up, name="mcc-import", daemon=True))
        WARMING[0].start()


WATCHERS = "mcc-configuration"  # the id of the file-watcher registration


@server.feature(t.INITIALIZED)
@quiet
def initialized(params: t.InitializedParams) -> None:
    """Ask the editor to tell when a configuration file changes on disk (LSP file watchers,
    registered dynamically where the client supports it; VS Code does, Neovim 0.10+ too). Without
    them the configuration is read again when the editor saves one (did_save)."""
    workspace = getattr(server.client_capabilities, "workspace", None)
    watched = getattr(workspace, "did_change_watched_files", None)
    if not getattr(watched, "dynamic_registration", False):
        return
    watchers = [t.FileSystemWatcher(glob_pattern=f"**/{name}") for name in CONFIG_NAMES]
    server.client_register_capability(t.RegistrationParams(registrations=[t.Registration(
        id=WATCHERS, method=t.WORKSPACE_DID_CHANGE_WATCHED_FILES,
        register_options=t.DidChangeWatchedFilesRegistrationOptions(watchers=watchers))]))


@server.feature(t.TEXT_DOCUMENT_DID_OPEN)
@quiet
def did_open(params: t.DidOpenTextDocumentParams) -> None:
    uri = params.text_document.uri
    if params.text_document.language_id in dialects.DIALECTS:
        server.documents.dialects[uri] = params.text_document.language_id
    configuration_moved(path_of(uri))  # its configuration files, as they are now
    server.documents.changed(uri, path_of(uri), reader(uri), delay=0)


@server.feature(t.TEXT_DOCUMENT_DID_CHANGE)
@quiet
def did_change(params: t.DidChangeTextDocumentParams) -> None:
    uri = params.text_document.uri
    if configuration_moved(path_of(uri)):
        reanalyse_all()
        return
    server.documents.changed(uri, path_of(uri), reader(uri))


STAMPS: dict[str, tuple] = {}  # directory of an open document -> configuration_stamp when last seen


def configuration_stamp(directory: str) -> tuple:
    """(folder, name, modification time, size) of every configuration file at or above `directory`
    (a few stat calls: cheap enough for every keystroke)."""
    out = []
    folder = os.path.abspath(directory)
    while True:
        for name in CONFIG_NAMES:
            try:
                found = os.stat(os.path.join(folder, name))
            except OSError:
                continue
            out.append((folder, name, found.st_mtime_ns, found.st_size))
        parent = os.path.dirname(folder)
        if parent == folder:
            return tuple(out)
        folder = parent


def configuration_moved(path: str) -> bool:
    """Whether a configuration file that may apply to `path` was created, changed or deleted since
    the last edit of a document there. Editors without file watchers (Neovim before 0.10, Helix,
    ...) never say so: the next keystroke then re-reads the configuration."""
    directory = os.path.dirname(os.path.abspath(path))
    stamp = configuration_stamp(directory)
    before = STAMPS.get(directory)
    STAMPS[directory] = stamp
    return before is not None and before != stamp


@server.feature(t.TEXT_DOCUMENT_DID_SAVE)
@quiet
def did_save(params: t.DidSaveTextDocumentParams) -> None:
    uri = params.text_document.uri
    if os.path.basename(path_of(uri)) in CONFIG_NAMES:
        reanalyse_all()
        return
    server.documents.changed(uri, path_of(uri), reader(uri), delay=0)


@server.feature(t.TEXT_DOCUMENT_DID_CLOSE)
@quiet
def did_close(params: t.DidCloseTextDocumentParams) -> None:
    uri = params.text_document.uri
    server.documents.closed(uri)
    server.documents.dialects.pop(uri, None)
    server.text_document_publish_diagnostics(t.PublishDiagnosticsParams(uri=uri, diagnostics=[]))


@server.feature(t.WORKSPACE_DID_CHANGE_WATCHED_FILES)
@quiet
def watched_files(params: t.DidChangeWatchedFilesParams) -> None:
    if any(os.path.basename(path_of(change.uri)) in CONFIG_NAMES for change in params.changes):
        reanalyse_all()


def reanalyse_all() -> None:
    server.documents.configuration_changed()
    for directory in list(STAMPS):
        STAMPS[directory] = configuration_stamp(directory)
    for uri in list(server.workspace.text_documents):
        server.documents.changed(uri, path_of(uri), reader(uri), delay=0)


# -- queries -------------------------------------------------------------------------------------

def located(uri: str, position: t.Position):
    snap = server.snapshot(uri)
    if snap is None:
        return None, 0
    return snap, convert.offset_of(snap.source, character(uri, position))


@server.feature(t.TEXT_DOCUMENT_HOVER)
@guarded
def on_hover(params: t.HoverParams):
    snap, offset = located(params.text_document.uri, params.position)
    return out(snap, hover.hover(snap, offset)) if snap else None


def current_line(uri: str, line: int) -> str:
    document = server.workspace.get_text_document(uri)
    lines = document.lines
    return lines[line].rstrip("\r\n") if 0 <= line < len(lines) else ""


@server.feature(t.TEXT_DOCUMENT_COMPLETION,
                t.CompletionOptions(trigger_characters=[" ", ",", "="], resolve_provider=False))
@guarded
def on_completion(params: t.CompletionParams):
    snap = server.snapshot(params.text_document.uri)
    if snap is None:
        return t.CompletionList(is_incomplete=True, items=[])
    uri = params.text_document.uri
    text = current_line(uri, params.position.line)
    answer = completion.complete(snap, text, character(uri, params.position).character, params.position.line)
    return answer if text.isascii() else server.units().out(answer, document_lines(uri))  # only that line's ranges


@server.feature(t.TEXT_DOCUMENT_SIGNATURE_HELP, t.SignatureHelpOptions(trigger_characters=[" ", ",", "="]))
@guarded
def on_signature(params: t.SignatureHelpParams):
    snap = server.snapshot(params.text_document.uri)
    if snap is None:
        return None
    text = current_line(params.text_document.uri, params.position.line)
    return completion.signature(snap, text, character(params.text_document.uri, params.position).character)


@server.feature(t.TEXT_DOCUMENT_DEFINITION)
@guarded
def on_definition(params: t.DefinitionParams):
    snap, offset = located(params.text_document.uri, params.position)
    return out(snap, navigation.definition(snap, offset)) if snap else None


@server.feature(t.TEXT_DOCUMENT_REFERENCES)
@guarded
def on_references(params: t.ReferenceParams):
    snap, offset = located(params.text_document.uri, params.position)
    return out(snap, navigation.references(snap, offset, params.context.include_declaration)) if snap else None


@server.feature(t.TEXT_DOCUMENT_DOCUMENT_HIGHLIGHT)
@guarded
def on_highlight(params: t.DocumentHighlightParams):
    snap, offset = located(params.text_document.uri, params.position)
    return out(snap, navigation.highlight(snap, offset)) if snap else None


@server.feature(t.TEXT_DOCUMENT_PREPARE_RENAME)
@guarded
def on_prepare_rename(params: t.PrepareRenameParams):
    snap, offset = located(params.text_document.uri, params.position)
    return out(snap, navigation.prepare_rename(snap, offset)) if snap else None


@server.feature(t.TEXT_DOCUMENT_RENAME, t.RenameOptions(prepare_provider=True))
@guarded
def on_rename(params: t.RenameParams):
    snap, offset = located(params.text_document.uri, params.position)
    if snap is None:
        return None
    return out(snap, navigation.rename(snap, offset, params.new_name))


@server.feature(t.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
@guarded
def on_document_symbol(params: t.DocumentSymbolParams):
    snap = server.snapshot(params.text_document.uri)
    return out(snap, outline.document_symbols(snap)) if snap else []


@server.feature(t.WORKSPACE_SYMBOL)
@guarded
def on_workspace_symbol(params: t.WorkspaceSymbolParams):
    snaps = {snap.uri: snap for snap in server.documents.latest.values()}
    found = outline.workspace_symbols(list(snaps.values()), params.query)
    return [out(snaps[s.location.uri], s) if s.location.uri in snaps else s for s in found]


@server.feature(t.TEXT_DOCUMENT_FOLDING_RANGE)
@guarded
def on_folding(params: t.FoldingRangeParams):
    snap = server.snapshot(params.text_document.uri)
    if snap is None:
        server.unanswered.add(params.text_document.uri)
        return []
    return outline.folding_ranges(snap)


@server.feature(t.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL, semantic.LEGEND)
@guarded
def on_semantic_full(params: t.SemanticTokensParams):
    snap = server.snapshot(params.text_document.uri)
    if snap is None:
        server.unanswered.add(params.text_document.uri)
        return t.SemanticTokens(data=[])
    return semantic.encode(snap, units=server.units())


@server.feature(t.TEXT_DOCUMENT_SEMANTIC_TOKENS_RANGE, semantic.LEGEND)
@guarded
def on_semantic_range(params: t.SemanticTokensRangeParams):
    snap = server.snapshot(params.text_document.uri)
    if snap is None:
        server.unanswered.add(params.text_document.uri)
        return t.SemanticTokens(data=[])
    return semantic.encode(snap, params.range.start.line, params.range.end.line, units=server.units())


@server.feature(t.TEXT_DOCUMENT_CODE_ACTION,
                t.CodeActionOptions(code_action_kinds=[t.CodeActionKind.QuickFix, t.CodeActionKind.Empty,
                                                       t.CodeActionKind.SourceFixAll, FIX_ALL],
                                    resolve_provider=True))
@server.thread()  # runs the compiler (fmt, lint --fix): off the protocol thread
@guarded
def on_code_action(params: t.CodeActionParams):
    uri = params.text_document.uri
    snap = server.snapshot(uri)
    if snap is None:
        return []
    selected = server.units().range_from_client(params.range, document_lines(uri))
    found = actions.code_actions(snap, selected, params.context)
    # the diagnostics an action names are the client's own, already in its units
    answer = [attrs.evolve(new, diagnostics=old.diagnostics) if isinstance(new, t.CodeAction) else new
              for old, new in zip(found, out(snap, found))]
    only = params.context.only
    if only and actions.fix_all_wanted(only):
        # asked for by kind (fix on save): computed now, from the editor's text (the latest analysis
        # may be a version behind, or have published the checks before the lint rules' fixes)
        action = fix_all(snap, uri)
        if action.edit.changes[uri]:
            answer.append(action)
    elif not only and actions.has_safe_fixes(snap):
        # the light bulb: the edits are computed only if it is chosen, where the editor can ask later
        answer.append(actions.fix_all_action(snap, data={"uri": uri}) if resolves_edits() else fix_all(snap, uri))
    return answer


def resolves_edits() -> bool:
    """Whether the client can ask for an action's edit later (codeAction/resolve)."""
    document = getattr(server.client_capabilities, "text_document", None)
    support = getattr(getattr(document, "code_action", None), "resolve_support", None)
    return "edit" in (getattr(support, "properties", None) or ())


def fix_all(snap, uri: str) -> t.CodeAction:
    """"Fix all" with its edits against the editor's current text, in the client's units."""
    document = server.workspace.get_text_document(uri).source
    edits = server.units().out(actions.fix_all_edits(snap, document), document_lines(uri))
    return actions.fix_all_action(snap, edits)


@server.feature(t.CODE_ACTION_RESOLVE)
@server.thread()  # runs the compiler (fmt, lint --fix): off the protocol thread
@guarded
def on_code_action_resolve(action: t.CodeAction):
    data = action.data if isinstance(action.data, dict) else {}
    uri = data.get("uri")
    snap = server.snapshot(str(uri)) if uri else None
    if snap is None or actions.kind_text(action.kind) != actions.FIX_ALL:
        return action
    return attrs.evolve(action, edit=fix_all(snap, str(uri)).edit)


@server.command("mcc.explain")  # actions.EXPLAIN
@guarded
def explain(*arguments):
    """The rule's explanation page: shown in the editor when it can show documents, and returned."""
    args = arguments[0] if len(arguments) == 1 and isinstance(arguments[0], (list, tuple)) else arguments
    code = str(args[0]).upper() if args else ""
    info = registry().get(code)
    if info is None:
        raise JsonRpcException(f"unknown diagnostic code {code!r}", code=REQUEST_FAILED)
    page = convert.rule_page(code, server.rules_url)
    window = getattr(server.client_capabilities, "window", None)
    if page and window is not None and getattr(window, "show_document", None):
        server.window_show_document_async(t.ShowDocumentParams(uri=page, external=page.startswith("http")))
    return info.page()


def formatted(uri: str, first: int | None = None, last: int | None = None):
    snap = server.snapshot(uri)
    if snap is None:
        return []
    document = server.workspace.get_text_document(uri).source
    return server.units().out(formatting.edits(snap, document, first, last), document_lines(uri))


@server.feature(t.TEXT_DOCUMENT_FORMATTING)
@server.thread()  # runs the compiler (fmt, lint --fix): off the protocol thread
@guarded
def on_formatting(params: t.DocumentFormattingParams):
    return formatted(params.text_document.uri)


@server.feature(t.TEXT_DOCUMENT_RANGE_FORMATTING)
@server.thread()  # runs the compiler (fmt, lint --fix): off the protocol thread
@guarded
def on_range_formatting(params: t.DocumentRangeFormattingParams):
    return formatted(params.text_document.uri, params.range.start.line, params.range.end.line)


@server.feature(t.TEXT_DOCUMENT_CODE_LENS, t.CodeLensOptions(resolve_provider=False))
@guarded
def on_code_lens(params: t.CodeLensParams):
    snap = server.snapshot(params.text_document.uri)
    return out(snap, lenses.code_lenses(snap)) if snap else []


@server.feature(t.TEXT_DOCUMENT_INLAY_HINT, t.InlayHintOptions(resolve_provider=False))
@guarded
def on_inlay_hint(params: t.InlayHintParams):
    snap = server.snapshot(params.text_document.uri)
    return out(snap, lenses.inlay_hints(snap, params.range.start.line, params.range.end.line)) if snap else []


STATUS = "mcc/status"


@server.feature(STATUS)
@guarded
def on_status(params):
    """mcc's own request: which version of a document the latest finished analysis is of, and
    whether its lint rules have run (editors can show it; the tests wait on it)."""
    uri = params.get("uri") if isinstance(params, dict) else getattr(params, "uri", None)
    snap = server.snapshot(str(uri)) if uri else None
    if snap is None:
        return {"uri": uri, "version": None, "complete": False, "dialect": None}
    return {"uri": uri, "version": snap.version, "complete": snap.complete, "dialect": snap.dialect,
            "diagnostics": len(snap.diagnostics), "timings": snap.timings}


@server.feature(t.SHUTDOWN)
@quiet
def on_shutdown(*_):
    if server._documents is not None:
        server._documents.shutdown()


def start(tcp: str | None = None, log_file: str | None = None, verbose: bool = False) -> None:
    # An analysis allocates hundreds of thousands of small objects while the last snapshots stay
    # alive; Python's default collection thresholds would rescan them many times per keystroke
    # (about 15% of a 3,000-line analysis). Cycles are still collected, only less often.
    gc.set_threshold(100_000, 50, 100)
    # The analysis thread holds the GIL for long stretches; the protocol thread must get it soon to
    # read a keystroke (which stops a stale analysis) and to send the diagnostics. Python hands the
    # GIL over every 5 ms by default; 1 ms makes each hop shorter at a negligible cost.
    sys.setswitchinterval(0.001)
    logging.basicConfig(filename=log_file, level=logging.DEBUG if verbose else logging.INFO,
                        format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    if not verbose:  # pygls logs every message it sends at INFO
        logging.getLogger("pygls").setLevel(logging.WARNING)
    if tcp:
        host, _, port = tcp.rpartition(":")
        server.start_tcp(host or "127.0.0.1", int(port))
    else:
        server.start_io()
