"""Which profile a file is checked and compiled for, and which profile a file seems written for.

One function, `choose`, decides the profile of a file for every command and for the editor server
(docs/CONFIGURATION.md, "Choosing the profile"). The first of these that names a profile of the
file's dialect wins:

1. `--profile` on the command line (`Settings.cli_profile`, or the profile a command passes);
2. a directive at the top of the file, in the dialect's own comment: `; mcc: profile=pmx-2ed-sa`
   (Arcus, X150), `' mcc: profile=lmm` (MCode); a name, or a path relative to the file;
3. `per-file-profiles` in the configuration: the first glob that matches the file;
4. `target` in the configuration (one profile, or one per dialect);
5. the dialect's default profile.

A directive that names no profile, or one of another dialect, is reported (G022) and ignored.

`suggest` is the other direction: a file checked with no profile chosen (step 5) that fails, and
shows the markers of another profile of its dialect (the profile file's `[detect]` table), gets
one diagnostic naming the profile it fits (G021) instead of the errors of the wrong product.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from functools import lru_cache

from mcc.compiler import dialects
from mcc.compiler.diagnostics import Diagnostic, Diagnostics
from mcc.compiler.profiles import Profile, ProfileError, builtin_names, load
from mcc.compiler.span import SourceFile, Span

DIRECTIVE = re.compile(r"mcc\s*:\s*profile\s*=\s*(?P<spec>\S+)\s*$", re.IGNORECASE)
HEAD_LINES = 50  # a directive is looked for in the comments before the first statement, this far

SOURCES = ("command line", "directive", "per-file-profiles", "target", "default")


@dataclass(frozen=True)
class Choice:
    """The profile of one file and why it is that one."""

    profile: Profile
    source: str  # one of SOURCES
    detail: str = ""  # the glob, the directive's line, ...
    diagnostics: tuple[Diagnostic, ...] = field(default=())

    @property
    def chosen(self) -> bool:
        """Whether anything named the profile (not the dialect's default)."""
        return self.source != "default"


def markers(dialect: str) -> str:
    """The comment markers a directive may be written with: every one the dialect reads
    (`Dialect.comment_markers`: MCode listings use the backtick as well as the apostrophe, Arcus
    reads "'" comments too, L1201)."""
    if dialect not in dialects.DIALECTS:
        return ";"
    found = dialects.get(dialect)
    return found.comment_markers or found.comment


def directive(source: SourceFile, dialect: str) -> tuple[str, Span] | None:
    """The profile named by a `mcc: profile=NAME` comment before the file's first statement, with
    the span of NAME."""
    marks = markers(dialect)
    for number, line in enumerate(source.text.split("\n")[:HEAD_LINES], 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped[0] not in marks:
            return None  # the first statement: a directive below it is not at the top
        body = stripped.lstrip(marks)
        found = DIRECTIVE.search(body)
        if found is not None and body[:found.start()].strip() == "":
            column = line.index(stripped) + (len(stripped) - len(body)) + found.start("spec")
            spec = found.group("spec")
            start = source.line_starts[number - 1] + column
            return spec, source.span(start, start + len(spec))
    return None


def resolve_spec(spec: str, base: str) -> str:
    """A profile name, or a path (relative to `base`, the file's directory) to a profile file."""
    if spec.endswith(".toml") or "/" in spec:
        return spec if os.path.isabs(spec) else os.path.join(base, spec)
    return spec


def choose(path: str, dialect: str, source: SourceFile | None, settings=None,
           cli: Profile | None = None) -> Choice:
    """The profile of the file `path` of `dialect` (its text in `source`), by the order above.
    `settings` is the file's configuration (compiler/config.py), `cli` a profile a command was
    given explicitly."""
    from mcc.compiler.config import load_profile

    problems = Diagnostics()
    if cli is not None and cli.dialect == dialect:
        return Choice(cli, "command line", cli.name)
    cli_spec = getattr(settings, "cli_profile", None)
    if cli_spec:
        prof = load_profile(cli_spec)
        if prof.dialect == dialect:
            return Choice(prof, "command line", prof.name)
    if source is not None:
        found = directive(source, dialect)
        if found is not None:
            spec, span = found
            prof = None
            try:
                prof = load_profile(resolve_spec(spec, os.path.dirname(os.path.abspath(path))))
            except (ProfileError, OSError, ValueError) as exc:
                problems.add("G022", span, f"{exc}: this `mcc: profile=` line is ignored (`mcc profiles` lists "
                                           "the built-in profiles)")
            if prof is not None and prof.dialect != dialect:
                problems.add("G022", span, f"profile '{spec}' is for {prof.dialect}, not for this {dialect} file: "
                                           "this `mcc: profile=` line is ignored")
            elif prof is not None:
                return Choice(prof, "directive", f"line {span.line}")
    if settings is not None:
        per_file = settings.profile_for_path(path, dialect)
        if per_file is not None:
            return Choice(load_profile(per_file[1]), "per-file-profiles", per_file[0], tuple(problems.items))
        spec = settings.profile_spec(dialect)
        if spec is not None:
            prof = load_profile(spec)
            if prof.dialect == dialect:
                return Choice(prof, "target", spec, tuple(problems.items))
    default = dialects.get(dialect).default_profile
    return Choice(load_profile(default), "default", default, tuple(problems.items))


# ---------------------------------------------------------------------------------------------
# Which profile a file seems written for


@dataclass(frozen=True)
class Detector:
    """A built-in profile's `[detect]` table: regular expressions on the upper-cased lines with
    comments removed, and how many of them must occur."""

    profile: str
    dialect: str
    markers: tuple[re.Pattern, ...]
    minimum: int


@lru_cache(maxsize=1)
def detectors() -> tuple[Detector, ...]:
    out = []
    for name in builtin_names():
        prof = load(name)
        table = prof.get("detect")
        if not isinstance(table, dict) or not table.get("markers"):
            continue
        out.append(Detector(prof.name, prof.dialect, tuple(re.compile(m) for m in table["markers"]),
                            int(table.get("min", 1))))
    return tuple(out)


COMMENT = re.compile(r"[;'`].*$")


def matches(source: SourceFile, detector: Detector) -> list[int]:
    """The first line each of the detector's markers occurs on (a marker that occurs nowhere adds
    nothing), when at least `minimum` of them occur; else []."""
    markers = detector.markers
    hits = _HITS.get(markers)
    if hits is None or len(hits) > 1 << 16:
        hits = _HITS[markers] = {}
    first: list[int | None] = [None] * len(markers)
    missing = len(first)
    for number, text in enumerate(source.text.split("\n"), 1):
        found = hits.get(text)
        if found is None:
            clean = COMMENT.sub("", text).upper()
            found = hits[text] = tuple(index for index, marker in enumerate(markers) if marker.search(clean))
        for index in found:
            if first[index] is None:
                first[index] = number
                missing -= 1
        if not missing:
            break
    evidence = [hit for hit in first if hit is not None]
    return sorted(set(evidence)) if len(evidence) >= detector.minimum else []


# per detector (its markers): the markers each line text holds (comment removed, upper-cased). The
# editor server asks again after every keystroke of a file with an error, and all but the edited
# line are the same (20 ms a keystroke on 3,000 Arcus lines without it)
_HITS: dict[tuple[re.Pattern, ...], dict[str, tuple[int, ...]]] = {}


def suggest(source: SourceFile, dialect: str, current: Profile, errors: int, analyze) -> Diagnostic | None:
    """G021 when another profile of the dialect fits a failing file better: its markers occur and
    the file, checked with it (`analyze(profile) -> error count`), has fewer errors. The profiles
    tried are those whose markers occur, most markers first."""
    candidates = []
    for detector in detectors():
        if detector.dialect != dialect or detector.profile == current.name:
            continue
        evidence = matches(source, detector)
        if evidence:
            candidates.append((len(evidence), detector, evidence))
    if not candidates:
        return None
    candidates.sort(key=lambda c: (-c[0], c[1].profile))
    scored = []
    for count, detector, evidence in candidates:
        left = analyze(load(detector.profile))
        if left < errors:
            scored.append((left, -count, detector.profile, evidence))
    if not scored:
        return None
    scored.sort()
    best = scored[0]
    fits = [s for s in scored if s[:2] == best[:2]]
    names = " or ".join(f"'{s[2]}'" for s in fits)
    evidence = best[3]
    shown = ", ".join(str(n) for n in evidence[:6])
    comment = markers(dialect)[0]
    left = "checks clean" if best[0] == 0 else f"has {best[0]} error{'s' if best[0] != 1 else ''}"
    diags = Diagnostics()
    diags.add("G021", source.line_span(evidence[0]),
              f"this file looks written for profile {names}, not {current.name}: read with {current.name} it has "
              f"{errors} error{'s' if errors != 1 else ''}, with {fits[0][2]} it {left} ({'line' if len(evidence) == 1 else 'lines'} {shown} {'shows' if len(evidence) == 1 else 'show'} it); "
              f"check it with `--profile {fits[0][2]}`, add `{comment} mcc: profile={fits[0][2]}` at the top of the "
              "file, or map it in `per-file-profiles`",
              notes=tuple(f"{source.path}:{n}: {source.line_text(n).strip()}" for n in evidence[:6]))
    return diags.items[0]
