"""What every backend produces: the device-ready text, a source map and statistics."""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import Span


@dataclass(slots=True)
class ListingLine:
    text: str
    sources: tuple[Span, ...] = ()


@dataclass
class Listing:
    dialect: str
    lines: list[ListingLine] = field(default_factory=list)
    stats: dict = field(default_factory=dict)
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    header: str = ""  # first lines of the human listing (e.g. the Arcus cost model in use)
    detail: list[tuple[str, tuple[Span, ...]]] | None = None  # finer listing rows (Arcus assembly lines)

    def emit(self, text: str, *sources: Span | None) -> None:
        self.lines.append(ListingLine(text, tuple(s for s in sources if s is not None)))

    @property
    def text(self) -> str:
        return "".join(line.text + "\n" for line in self.lines)

    def source_map(self) -> list[dict]:
        """For each output line (1-based), the source lines it came from."""
        return [
            {"line": number, "sources": sorted({(s.file, s.line) for s in line.sources})}
            for number, line in enumerate(self.lines, 1)
        ]

    def render(self) -> str:
        """The human listing: numbered output lines (or the finer detail rows) with their sources."""
        rows = self.detail if self.detail is not None else [(l.text, l.sources) for l in self.lines]
        width = max((len(text) for text, _ in rows), default=0)
        out = []
        if self.header:
            out += [self.header.rstrip("\n"), ""]
        for number, (text, sources) in enumerate(rows, 0 if self.detail is not None else 1):
            where = ", ".join(f"{s.line}" for s in sorted(set(sources), key=lambda s: s.line))
            out.append(f"{number:5}  {text:<{width}}  ; src {where or '-'}")
        return "\n".join(out) + "\n"


def axis_sets_written(module, dialect: str, title: str):
    """(module, None) with another dialect's axis sets (Arcus HSPDa/LSPDa/ACCa, used only once all
    are set, L447-L457) as a target applies an axis's own speeds at once, or (None, a listing that
    refuses the program on the setting's line) when a set is complete on some paths only."""
    from mcc.compiler import in_force

    try:
        return in_force.without_axis_sets(module), None
    except in_force.Unresolved as exc:
        refused = Listing(dialect)
        refused.diagnostics.add("G003", exc.span or Span(module.path or "-", 1, 1, 1, 1),
                                f"this setting cannot be written in {title}: {exc}")
        return None, refused
