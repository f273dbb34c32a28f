"""No input, however malformed, makes mcc raise: random and mutated text through every command.

Three kinds of input, for each dialect: random text and token soup (check and compile, in
memory), the samples mutated the way a fuzzer mutates files (deleted and duplicated lines,
truncation, huge numbers, long expressions, random bytes, NUL, CR-only line ends, a BOM, Latin-1
and UTF-16 text) written to disk and run through every command (check, lint, lint --fix, fmt and
compile to every target), and generated programs of any nesting depth and length. The
counts of examples keep each test to a few seconds.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, dialects_with, sample_files
from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine, formatting

ALPHABET = st.characters(codec="utf-8", exclude_categories=("Cs",))
TOKENS = {
    "mcode": ["MA", "MR", "PG", "LB", "BR", "CL", "RT", "E", "VA", "PR", "=", ",", "\"", "`", "'", "-", "*",
              "!", "^", "1", "100", "K1", "G1", " ", "\n", "IS", "S1", "<>", "I1", "F1", "CS", ";", "H"],
    "arcus": ["IF", "ELSE", "ELSEIF", "ENDIF", "WHILE", "ENDWHILE", "SUB", "ENDSUB", "GOSUB", "END", "X", "Y",
              "V1", "=", "+", "-", ";", "HSPDX", "JOGX+", "DO7", "1000", ":", " ", "\n", "!=", "~", "WAITX"],
    "x150": ["XD1", "XT", "XE1", "1A10", "V5", "D-100", "G", "L5", "N", "IF(", ")", "VAR1", "=", " ", "\n", ";",
             "\"", "1OUT3B", "TRE_X1", "ELSE", "NIF", "WHILE(", "NWHILE", "REPEAT", "UNTIL(", "XR2", "AND"],
}
# A long expression in each dialect's own spelling: `count` operators on one line.
LONG_EXPRESSION = {
    "mcode": lambda count: "R1=" + "+".join(["R2"] * (count + 1)),
    "arcus": lambda count: "V1=" + "+".join(["V2"] * (count + 1)),
    "x150": lambda count: "1VAR1=" + "*".join(["2"] * (count + 1)),
}
TARGETS = ("mcode", "arcus", "x150")


def mutate(text: str, data) -> str:
    ops = data.draw(st.lists(st.tuples(st.integers(0, 3), st.integers(0, max(0, len(text))), st.text(ALPHABET, max_size=4)),
                             max_size=6))
    for kind, pos, piece in ops:
        if kind == 0:
            text = text[:pos] + piece + text[pos:]
        elif kind == 1:
            text = text[:pos] + text[pos + len(piece) + 1:]
        elif kind == 2:
            text = text[:pos] + piece + text[pos + 1:]
        else:
            text = text[:pos] + text[pos:pos + 8] + text[pos:]
    return text


def run_everything(dialect: str, text: str) -> None:
    for result in (driver.check_file(f"f{EXTENSIONS[dialect]}", dialect, text=text),
                   driver.compile_file(f"f{EXTENSIONS[dialect]}", dialect, text=text)):
        internal = [d.message for d in result.diagnostics if d.kind.value == "internal"]
        assert not internal, internal


FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_random_text_never_crashes(dialect: str, data) -> None:
    text = data.draw(st.text(ALPHABET, max_size=200))
    run_everything(dialect, text)


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_token_soup_never_crashes(dialect: str, data) -> None:
    pieces = data.draw(st.lists(st.sampled_from(TOKENS[dialect]), max_size=40))
    run_everything(dialect, "".join(pieces))


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@FUZZ
@given(data=st.data())
def test_mutated_samples_never_crash(dialect: str, data) -> None:
    samples = sample_files(dialect)
    if not samples:
        pytest.skip(f"no {dialect} samples")
    text = data.draw(st.sampled_from(samples)).read_text(encoding="utf-8")
    run_everything(dialect, mutate(text, data))


# Every command, on files a fuzzer would write ---------------------------------------------------

def file_mutation(dialect: str, text: str, data) -> bytes:
    """One to three of the mutations a file fuzzer makes, then an encoding."""
    lines = text.split("\n")
    for _ in range(data.draw(st.integers(1, 3), label="mutations")):
        kind = data.draw(st.sampled_from(["delete", "duplicate", "truncate", "number", "expression", "bytes",
                                          "nul"]), label="kind")
        at = data.draw(st.integers(0, max(0, len(lines) - 1)), label="line")
        if kind == "delete" and lines:
            del lines[at]
        elif kind == "duplicate" and lines:
            lines[at:at] = [lines[at]] * data.draw(st.integers(1, 50), label="copies")
        elif kind == "truncate":
            joined = "\n".join(lines)
            lines = joined[:data.draw(st.integers(0, len(joined)), label="length")].split("\n")
        elif kind == "number":
            digits = "9" * data.draw(st.sampled_from([20, 41, 400, 5000]), label="digits")
            line = lines[at] if lines else ""
            cut = data.draw(st.integers(0, len(line)), label="column")
            lines[at:at + 1] = [line[:cut] + digits + line[cut:]]
        elif kind == "expression":
            count = data.draw(st.sampled_from([10, 99, 100, 3000]), label="operators")
            lines.insert(at, LONG_EXPRESSION[dialect](count))
        elif kind == "bytes":
            noise = data.draw(st.text(ALPHABET, min_size=1, max_size=8), label="noise")
            line = lines[at] if lines else ""
            cut = data.draw(st.integers(0, len(line)), label="column")
            lines[at:at + 1] = [line[:cut] + noise + line[cut:]]
        elif kind == "nul":
            lines.insert(at, "\0" * data.draw(st.integers(1, 4), label="nuls"))
    text = "\n".join(lines)
    newline = data.draw(st.sampled_from(["\n", "\r\n", "\r"]), label="newline")
    text = text.replace("\n", newline)
    encoding = data.draw(st.sampled_from(["utf-8", "utf-8-bom", "latin-1", "utf-16"]), label="encoding")
    if encoding == "utf-8-bom":
        return b"\xef\xbb\xbf" + text.encode("utf-8")
    if encoding == "latin-1":
        return ("µ±° " + text).encode("latin-1", errors="replace")
    return text.encode(encoding)


def every_command(dialect: str, data: bytes) -> None:
    """check, compile to every target, lint, lint --fix, fmt --check and fmt on one file."""
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / f"fuzz{EXTENSIONS[dialect]}")
        Path(path).write_bytes(data)
        results = [driver.check_file(path)] + [driver.compile_file(path, target=t) for t in TARGETS]
        found = [d for r in results for d in r.diagnostics]
        found += engine.lint_file(path, Settings()).diagnostics
        found += engine.lint_file(path, Settings(), engine.Options(fix=True, unsafe_fixes=True)).diagnostics
        internal = [f"{d.code} {d.message}" for d in found if d.kind.value == "internal"]
        assert not internal, internal
        for options in (formatting.Options(check=True), formatting.Options()):
            outcome = formatting.format_file(path, Settings(), options)
            assert "internal error" not in outcome.error, outcome.error


ON_DISK = settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@ON_DISK
@given(data=st.data())
def test_fuzzed_files_through_every_command(dialect: str, data) -> None:
    samples = sample_files(dialect)
    if not samples:
        pytest.skip(f"no {dialect} samples")
    text = data.draw(st.sampled_from(samples)).read_text(encoding="utf-8")
    every_command(dialect, file_mutation(dialect, text, data))


# Depth and length -------------------------------------------------------------------------------

def free_names() -> list[str]:
    """MCode's two-character user names that no command, variable or flag takes."""
    from mcc.compiler.mcode import catalog

    cat = catalog.load()
    letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    return [a + b for a in letters for b in letters + "0123456789"
            if cat.lookup(a + b) is None and not cat.is_reserved(a + b) and a + b not in cat.legacy]


def nested(dialect: str, kind: str, depth: int) -> str:
    """`depth` blocks nested in one another, in the dialect's own constructs."""
    if dialect == "arcus":
        opener = {"if": "IF V1<{i}", "while": "WHILE V1<{i}", "ifelse": "IF V1<{i}"}[kind]
        closer = {"if": ["ENDIF"], "while": ["ENDWHILE"], "ifelse": ["ELSE", "V2=V2+1", "ENDIF"]}[kind]
        head = [line for i in range(depth) for line in (opener.format(i=i + 1), "V1=V1+1")]
        return "\n".join(["V1=0", "V2=0", *head, *(closer * depth), "END"]) + "\n"
    if dialect == "x150":
        opener = {"if": "1IF(VAR1<{i})", "while": "1WHILE(VAR1<{i})", "ifelse": "1IF(VAR1<{i})"}[kind]
        closer = {"if": ["1NIF"], "while": ["1NWHILE"], "ifelse": ["1ELSE", "1VAR2=VAR2+1", "1NIF"]}[kind]
        head = [line for i in range(depth) for line in (opener.format(i=i + 1), "1VAR1=VAR1+1")]
        return "\n".join(["1XE1", "1XD1", *head, *(closer * depth), "1XT", "1XR1"]) + "\n"
    # MCode has no blocks: nest subroutine calls (CL) or chain branches (BR)
    names = free_names()
    names = (names * (depth // len(names) + 1))[:depth + 1]
    body = ["PG 1", f"LB {names[0]}"]
    for i in range(depth):
        if kind == "while":  # chained BR, each label looping on an input
            body += ["MR 100", f"BR {names[i]}, I1=1", f"BR {names[i + 1]}", f"LB {names[i + 1]}"]
        else:
            body += [f"CL {names[i + 1]}", "RT" if i else "E", f"LB {names[i + 1]}"]
    body += ["MR 1", "RT" if kind != "while" else "E", "PG", "S"]
    return "\n".join(body) + "\n"


def program_of(dialect: str, lines: int) -> str:
    """A program of about `lines` lines: loops with conditions inside, labels, calls."""
    block = {
        "arcus": ["V1=0", "WHILE V1<10", "IF V2=1", "X1000", "WAITX", "ELSEIF V2=2", "V3=V3+1", "ELSE", "DO1=1",
                  "ENDIF", "V1=V1+1", "ENDWHILE"],
        "x150": ["1L5", "1IF(VAR1>5 AND IN_XX1)", "1D4000", "1G", "1ELSE", "1VAR1=VAR1+1", "1NIF",
                 "1WHILE(VAR2<10)", "1VAR2=VAR2+1", "1NWHILE", "1N"],
        "mcode": ["LB {a}", "MR 100", "H", "BR {a}, I1=1", "IC R1", "CL {b}, R1>3", "BR {c}", "LB {b}", "O1=1", "RT",
                  "LB {c}"],
    }[dialect]
    out: list[str] = []
    if dialect == "x150":
        out += ["1XE1", "1XD1"]
    if dialect == "mcode":
        out += ["PG 1"]
    i = 0
    while len(out) < lines:
        names = {"a": f"A{i % 100:02}", "b": f"B{i % 100:02}", "c": f"C{i % 100:02}"}
        out += [line.format(**names) for line in block]
        i += 1
    out += {"arcus": ["END"], "x150": ["1XT", "1XR1"], "mcode": ["E", "PG", "S"]}[dialect]
    return "\n".join(out) + "\n"


DEEP = settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@DEEP
@given(kind=st.sampled_from(["if", "while", "ifelse"]), depth=st.integers(1, 520))
def test_any_nesting_depth_through_every_command(dialect: str, kind: str, depth: int) -> None:
    every_command(dialect, nested(dialect, kind, depth).encode())


@pytest.mark.parametrize("dialect", dialects_with("backend"))
@settings(max_examples=3, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(lines=st.integers(1, 2000))
def test_any_program_length_through_every_command(dialect: str, lines: int) -> None:
    every_command(dialect, program_of(dialect, lines).encode())
