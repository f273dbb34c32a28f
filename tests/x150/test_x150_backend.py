"""The X150 backend: canonical text, statistics, and IR it cannot write."""

from __future__ import annotations

import ast
from pathlib import Path

from conftest import ROOT, sample_files
from mcc.backends import x150 as backend
from mcc.compiler import driver, ir, profiles
from mcc.compiler.span import Span

from x150_helpers import check, compile_, output

PROFILE = profiles.load("x150-pdhx")
SPAN = Span("m", 1, 1, 1, 2, 0, 1)


def test_canonical_form():
    text = "xd1 ;stored\n1a10 v5 d4000 g\nIF (IN_1) gosub2 NIF GOTO 3\nxt\nSAVE\n"
    # the modes are written before the first move of a sequence (the device may be in any mode then)
    # SV is device specific (parker-x150.md L181, L4087): written with the profile's device, 1SV
    assert output(text) == ["XE1", "XD1", "1A10", "V5", "MN", "MPI", "D4000", "G", "IF(IN_1)", "XR2", "NIF", "XG3",
                            "XT", "1SV"]


def test_addresses_of_a_device_sequence_are_written_on_every_line():
    assert output("1XE1\n1XD1\nA10\n1XT\n1SV\n") == ["1XE1", "1XD1", "1A10", "1XT", "1SV"]


def test_b_prefix_and_comments_inside_sequences():
    lines = output("1XE1\n1XD1 ; a comment\n1BCPE2000 ; another\n1BY\n1XT\n1SV\n")
    assert lines == ["1XE1", "1XD1", "1BCPE2000", "1BY", "1XT", "1SV"]


def test_stats_count_sequence_memory_like_the_check():
    result = compile_("1XE1\n1XD1\n1A10\n1MN\n1MPI\n1G\n1XT\n1SV\n")
    stats = result.listing.stats
    # 1A10 (4+1) 1MN (3+1) 1MPI (4+1) 1G (2+1) 1XT (3+1): XEn and XDn are sent, not stored
    assert result.listing.text.splitlines()[2:7] == ["1A10", "1MN", "1MPI", "1G", "1XT"]
    assert (stats["sequences"], stats["sequence_bytes"], stats["sequence_budget"]) == (1, 21, 8000)
    assert stats["sequence_bytes_by_device"] == {"1": 21}
    assert "X124" not in [d.code for d in check("1XE1\n1XD1\n" + "1A10\n" * 300 + "1XT\n").diagnostics]
    assert "X124" in [d.code for d in check("1XE1\n1XD1\n" + "1A10\n" * 400 + "1XT\n").diagnostics]


def test_stats_of_every_sample_agree_with_the_memory_check():
    for path in sample_files("x150"):
        result = driver.compile_file(str(path), "x150")
        assert result.listing is not None, path
        assert result.listing.stats["sequence_bytes"] > 0
        assert result.listing.stats["sequence_budget"] == 8000


def source_lines(text: str) -> list[tuple[str, list[int]]]:
    listing = compile_(text).listing
    return [(line.text, sorted({s.line for s in line.sources})) for line in listing.lines]


def test_source_map_points_at_the_source_lines():
    rows = source_lines("1XE1\n1XD1\n1MN\n1MPI\n1D4000\n1G\n1XT\n1XR1\n1SV\n")
    assert rows == [("1XE1", [1]), ("1XD1", [2]), ("1MN", [5]), ("1MPI", [5]), ("1D4000", [5]), ("1G", [6]),
                    ("1XT", [7]), ("1XR1", [8]), ("1SV", [9])]


def test_every_construct_line_maps_to_its_own_source_line():
    """Issue 12: XE, ELSE, NIF and the XT after an XG point at their own lines."""
    text = ("1XE2\n1XD2\n1T1\n1XT\n1XE1\n1XD1\nIF(IN_1)\n1T1\nELSE\n1T2\nNIF\n"
            "WHILE(VAR1<3)\nVAR1=VAR1+1\nNWHILE\nL3\n1T3\nN\nREPEAT\n1T4\nUNTIL(IN_X1)\n1XG2\n1XT\n")
    rows = source_lines(text)
    lines = text.splitlines()
    for written, sources in rows:
        assert len(sources) == 1, written
        assert lines[sources[0] - 1].upper().endswith(written.lstrip("1")), (written, sources)


def module(*routines: ir.Routine, dialect: str = "x150") -> ir.Module:
    return ir.Module(dialect, "test", routines=list(routines))


def block(label: str, ops=(), term=None) -> ir.Block:
    return ir.Block(label, list(ops), term or ir.FallOff(SPAN), SPAN)


def test_foreign_native_is_g003_not_a_crash():
    routine = ir.Routine("main", ir.RoutineKind.MAIN, [block("a", [ir.Native("mcode", "IS", (), span=SPAN)])], SPAN)
    listing = backend.emit(module(routine, dialect="mcode"), PROFILE)
    assert [d.code for d in listing.diagnostics] == ["G003"]
    assert [t for t in listing.text.splitlines() if not t.startswith(";")] == ["XE1", "XD1", "XT"]


def test_foreign_routines_get_free_sequence_numbers_and_modes():
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("a", [
        ir.Move(ir.MoveMode.ABSOLUTE, (("1", ir.Const(2000, ir.Unit.STEPS)),), span=SPAN),
        ir.Delay(ir.Const(250, ir.Unit.MS), SPAN), ir.Call("sub", None, SPAN)])], SPAN)
    sub = ir.Routine("sub", ir.RoutineKind.SUBROUTINE, [block("b", [ir.Delay(ir.Const(1, ir.Unit.S), SPAN)])], SPAN,
                     number=64)
    listing = backend.emit(module(main, sub, dialect="mcode"), PROFILE)
    assert not listing.diagnostics.items
    # no WaitMotion after the move: the delay runs during it, which is X150's MQ (MN would wait, L2631)
    assert [t for t in listing.text.splitlines() if not t.startswith(";")] == [
        "XE1", "XD1", "1MQ", "1MPA", "1D2000", "1G", "T0.25", "XR64", "XT", "XE64", "XD64", "T1", "XT"]


def test_a_save_in_a_sequence_is_refused():
    """parker-x150.md L4087: SV is "Immediate, Device Specific": a sequence cannot store it (it
    would run at download time, X113), so a Save inside a routine is refused with its line."""
    sub = ir.Routine("sub", ir.RoutineKind.SUBROUTINE, [block("b", [ir.Save(SPAN)])], SPAN, number=64)
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("a", [ir.Call("sub", None, SPAN)])], SPAN)
    listing = backend.emit(module(main, sub, dialect="mcode"), PROFILE)
    assert [(d.code, "L4087" in d.message) for d in listing.diagnostics.items] == [("G003", True)]


def test_irreducible_flow_is_x201():
    # a jump back into the middle of an IF: no X150 construct says that
    blocks = [block("a", term=ir.Branch(ir.InputMatch(ir.Pattern("_1")), "b", "c", SPAN)),
              block("b", [ir.Delay(ir.Const(1, ir.Unit.S))], ir.Jump("c", SPAN)),
              block("c", [ir.Delay(ir.Const(2, ir.Unit.S))], ir.Branch(ir.InputMatch(ir.Pattern("_01")), "b", "d", SPAN)),
              block("d")]
    listing = backend.emit(module(ir.Routine("SEQ1", ir.RoutineKind.MAIN, blocks, SPAN, 1)), PROFILE)
    assert "X201" in [d.code for d in listing.diagnostics]
    assert "T1" not in listing.text  # refused: written flat it would do something else


def test_expression_that_needs_parentheses_is_x202():
    value = ir.BinOp("*", ir.Var("VAR2"), ir.BinOp("+", ir.Var("VAR3"), ir.Const(1)))
    routine = ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, [block("a", [ir.Assign(ir.Var("VAR1"), value, SPAN)])])
    listing = backend.emit(module(routine), PROFILE)
    assert [d.code for d in listing.diagnostics] == ["X202"]


def test_output_of_every_sample_checks_clean():
    for path in sample_files("x150"):
        text = driver.compile_file(str(path), "x150").listing.text
        again = check(text)
        assert not [d for d in again.diagnostics if d.severity.value == "error"], path


def imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
    return found


def test_backend_does_not_depend_on_the_syntax_tree():
    """backends/x150.py and what it uses (writer, structurer, naming) see only the IR and the catalog."""
    forbidden = {"mcc.compiler.x150.syntax", "mcc.compiler.x150.parser", "mcc.compiler.x150.tokens",
                 "mcc.compiler.x150.lower", "mcc.compiler.x150.checks", "mcc.compiler.x150.structure"}
    for name in ("backends/x150/__init__.py", "backends/x150/writer.py", "compiler/x150/naming.py",
                 "backends/structure.py", "compiler/x150/catalog.py"):
        assert not imports(ROOT / name) & forbidden, name


def test_loops_and_branches_of_other_dialects_are_structured():
    """MCode's `BR head, c` (loop while c) and `BR past, c` become REPEAT..UNTIL(NOT c) and IF(NOT c)."""
    q1 = ir.Var("Q1")
    blocks = [
        block("A1", [ir.Assign(q1, ir.BinOp("+", q1, ir.Const(1)), SPAN)],
              ir.Branch(ir.Compare("<", q1, ir.Const(5)), "A1", "b", SPAN)),
        block("b", [], ir.Branch(ir.Compare("!=", q1, ir.Const(5)), "d", "c", SPAN)),
        block("c", [ir.Delay(ir.Const(1, ir.Unit.S), SPAN)], ir.Jump("d", SPAN)),
        block("d", [], ir.End(SPAN)),
    ]
    main = ir.Routine("A1", ir.RoutineKind.MAIN, blocks, SPAN)
    start = ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, [block("%imm", [], ir.Jump("A1", SPAN))], SPAN)
    mod = module(start, main, dialect="mcode")
    mod.variables["Q1"] = ir.Variable("Q1", ir.VarType.INT32, ir.Const(0))
    listing = backend.emit(mod, PROFILE)
    assert not listing.diagnostics.items, [d.message for d in listing.diagnostics]
    assert [t for t in listing.text.splitlines() if not t.startswith(";")] == [
        "VAR1=0", "XE1", "XD1", "REPEAT", "VAR1=VAR1+1", "UNTIL(VAR1>5 OR VAR1=5)",
        "IF(VAR1=5)", "T1", "NIF", "HALT", "XT", "XG1"]


def test_conditions_x150_cannot_say_are_x202():
    cond = ir.Logic("and", ir.Compare("!=", ir.Var("VAR1"), ir.Const(1)), ir.InputMatch(ir.Pattern("_1")))
    blocks = [block("a", term=ir.Branch(cond, "b", "c", SPAN)), block("b", [ir.Save(SPAN)], ir.Jump("c", SPAN)),
              block("c")]
    listing = backend.emit(module(ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, blocks, SPAN)), PROFILE)
    assert [d.code for d in listing.diagnostics] == ["X202"]  # VAR1<1 OR VAR1>1 AND IN_1: three terms


def test_a_counted_loop_whose_body_returns_early_keeps_its_count():
    """The structurer nests what follows an IF that returns into its ELSE; the L loop's closing
    N (the hidden counter's decrement) must still be found after it, not written as a variable."""
    text = "XE1\nXD1\nL(VAR2)\nWHILE(IN_1)\nXRT\nNWHILE\nIF(VAR1>5)\nXRT\nNIF\nN\nXT\n"
    assert output(text) == ["XE1", "XD1", "L(VAR2)", "IF(IN_1)", "XRT", "NIF", "IF(VAR1>5)", "XRT", "NIF", "N", "XT"]


def test_a_counted_loop_left_from_its_middle_counts_in_a_free_variable():
    """The structure makes this L loop a WHILE that leaves by XRT; its hidden counter becomes the
    highest free VARn, with its count, and the program behaves as its source (simulated)."""
    from mcc.sim.verify import check_translation

    text = ("XE1\nXD1\nVAR1=6\nIF(VAR1>5)\nL3\nIF(VAR2>1)\nREPEAT\nUNTIL(VAR3>2)\nXRT\nNIF\n1D100\n1G\nN\n"
            "XRT\nNIF\nXT\nXR1\n")
    result = compile_(text)
    assert [d.code for d in result.diagnostics if d.severity.value != "note"].count("X215") == 1
    lines = output(text)
    assert "VAR50=3" in lines and "VAR50=VAR50-1" in lines and not result.has_errors
    assert not check_translation("t.x150", "x150", text, result.listing.text)


def test_input_conditions_are_written_as_one_x150_pattern():
    # dedicated and user levels joined by AND are one pattern; the `_` is always written (X131)
    assert output("1TRE_X1\n1TRNX1\n1IF(IN1_1X AND VAR1>2)\n1T1\n1NIF\n") == [
        "1TRE_X1", "1TRNX1_", "1IF(IN1_1 AND VAR1>2)", "1T1", "1NIF"]
    # input levels of another dialect's IR: input 3 on and the home switch off
    cond = ir.Logic("and", ir.Compare("=", ir.Status("input", "", 3), ir.Const(1)),
                    ir.Compare("=", ir.Status("home_switch", ""), ir.Const(0)))
    routine = ir.Routine("main", ir.RoutineKind.MAIN, [block("a", [ir.WaitInput(cond, SPAN)])], SPAN)
    assert "TREXX0_XX1" in backend.emit(module(routine, dialect="mcode"), PROFILE).text.splitlines()
    # one input at two levels is no pattern: refused, not written as something else
    both = ir.Logic("and", ir.InputMatch(ir.Pattern("1")), ir.InputMatch(ir.Pattern("0")))
    routine = ir.Routine("main", ir.RoutineKind.MAIN, [block("a", [ir.WaitInput(both, SPAN)])], SPAN)
    assert [d.code for d in backend.emit(module(routine, dialect="mcode"), PROFILE).diagnostics] == ["G003"]


def test_an_xg_inside_an_if_is_written_after_its_nif():
    """An XG out of an IF leaves the IF open (L1794, X112): the backend lifts it after the NIF when
    the other path never gets there, so the output checks clean."""
    text = "1XE2\n1XD2\n1NIF\n1T2\n1XT\n1XE1\n1XD1\n1IF(IN_1)\n1T1\n1XG2\n1NIF\n1T3\n1XRT\n1XT\n1XR1\n"
    written = output(text)
    assert written[written.index("1XD1") + 1:written.index("1XT", written.index("1XD1"))] == [
        "1IF(IN_1)", "1T1", "1ELSE", "1T3", "1XRT", "1NIF", "1XG2"]
    again = driver.check_file("out.x150", "x150", text="\n".join(written) + "\n")
    assert not [d.code for d in again.diagnostics if d.code == "X112"]


def test_a_continuous_g_after_a_computed_distance_keeps_its_unknown_direction():
    """MC G runs in D's direction: after D(VAR1) that is known only at run time, so the factory
    default (a positive D, L810) must not show through as a forward slew."""
    module = compile_("1XE1\n1XD1\n1D(VAR1)\n1MC\n1G\n1XT\n").analysis.module
    ops = [op for _, block in module.blocks() for op in block.ops]
    assert not any(isinstance(op, ir.Slew) for op in ops)
    assert any(isinstance(op, ir.Native) and op.mnemonic == "G" for op in ops)


def test_a_while_on_a_negated_condition_x150_cannot_write_is_an_if_around_a_repeat():
    """Found by the generated-program property: an L loop left from its middle whose exit test is
    NOT(IN_X01 OR VAR1>5) (X150 has no NOT); WHILE(NOT c) B is written IF(c) ELSE REPEAT B UNTIL(c) NIF."""
    text = ("1XE54\n1XD54\n1L(VAR2)\n1IF(IN_X01 OR VAR1>5)\n1REPEAT\n1UNTIL(IN_X01 OR VAR2<3)\n1XRT\n1NIF\n1G\n1N\n"
            "1VAR3=VAR1+2\n1XRT\n1XST0\n1XT\n")
    result = driver.compile_file("w.x150", "x150", text=text, opt_level="O0")
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    lines = result.listing.text.splitlines()
    start = lines.index("1IF(IN_X01 OR VAR1>5)")
    assert lines[start + 1:start + 3] == ["1ELSE", "1REPEAT"] and "1UNTIL(IN_X01 OR VAR1>5)" in lines
    again = driver.compile_file("w2.x150", "x150", text=result.listing.text, opt_level="O0")
    assert not again.has_errors and again.listing.text == result.listing.text


def test_reports_and_transmissions_are_written_back_as_the_commands_they_came_from():
    """TX (parker-x150.md L4463-L4483), QS (L3209-L3217), INL and OUTL reports and levels
    (L2131-L2141, L3034-L3051) lower to prints and settings the writer turns back into them."""
    lines = output("1XE1\n1XD1\n1TX1,0,3,3V\n1TX2,1,0,2D\n1QS\n1INL\n1OUTL\n1INLXXXX10X_1XX1X0XX\n1OUTLXX10X1\n"
                   "1XT\n1SV\n")
    assert lines == ["1XE1", "1XD1", "1TX1,0,3,3V", "1TX2,1,0,2D", "1QS", "1INL", "1OUTL", "1INLXXXX10_1XX1X0",
                     "1OUTLXX10X1", "1XT", "1SV"]


def test_a_print_in_a_format_x150_has_no_command_for_is_refused():
    """X150 sends a formatted value only as TX or as its reports (L4463-L4483): a print of a
    variable in another format (four decimals and a second item) has no X150 form."""
    mod = check("VAR1=1\n1TX1,0,3,3V\n").analysis.module
    for _, block in mod.blocks():
        for index, op in enumerate(block.ops):
            if isinstance(op, ir.Print):
                block.ops[index] = ir.Print(op.items + (ir.Text("!"),), True, op.span, formats=op.formats)
    written = backend.write(mod, profiles.load("x150-pdhx"))
    assert any(d.code == "G003" and "TX" in d.message for d in written.diagnostics)
