"""Lowering to the shared IR: routines, constructs as blocks, neutral operations, axes."""

from __future__ import annotations

from mcc.compiler import ir

from x150_helpers import assert_well_formed, check, module


def ops(routine: ir.Routine) -> list:
    return [op for block in routine.blocks for op in block.ops]


def test_routines_in_stream_order_with_names_numbers_and_kinds():
    mod = module("""
        1CUR4000
        1XE20
        1XD20
        1O0
        1XT
        1XE10
        1XD10
        1XR11
        1XT
        1XE11
        1XD11
        1G
        1XT
        XE12
        XD12
        G
        XT
        1XFK20
        1XP10
        1SV
    """)
    assert [(r.name, r.kind.value, r.number) for r in mod.routines] == [
        ("immediate@1", "immediate", None), ("SEQ20@1", "handler", 20), ("SEQ10@1", "powerup", 10),
        ("SEQ11@1", "subroutine", 11), ("SEQ12", "main", 12), ("immediate.2@1", "immediate", None)]
    handlers = [op for op in ops(mod.routines[-1]) if isinstance(op, ir.SetHandler)]
    assert [(h.event, h.routine) for h in handlers] == [("fault", "SEQ20@1"), ("power", "SEQ10@1")]
    assert isinstance(ops(mod.routines[-1])[-1], ir.Save)
    assert_well_formed(mod)


def test_erase_before_define_is_part_of_the_definition():
    mod = module("1XE1\n1XD1\n1G\n1XT\n")
    assert [r.kind for r in mod.routines] == [ir.RoutineKind.MAIN]


def test_loop_uses_a_hidden_counter():
    mod = module("L5\nG\nN\n")
    routine = mod.routines[0]
    assert "%L1" in mod.variables and mod.variables["%L1"].type is ir.VarType.INT32
    entry, body, after = routine.blocks
    assert isinstance(entry.ops[-1], ir.Assign) and entry.ops[-1].value.value == 5
    assert isinstance(entry.terminator, ir.Jump) and entry.terminator.target == body.label
    latch = body.terminator
    assert isinstance(latch, ir.Branch) and (latch.then, latch.otherwise) == (body.label, after.label)
    assert latch.cond.op == "!=" and latch.cond.left.name == "%L1"
    assert_well_formed(mod)


def test_if_else_while_repeat_shapes():
    mod = module("""
        IF(VAR1>5 AND IN_XX1)
        XR1
        ELSE
        XR2
        NIF
        WHILE(IN_1)
        T1
        NWHILE
        REPEAT
        G
        UNTIL(IN_10 OR IN_01)
    """)
    blocks = mod.routines[0].blocks
    branch = blocks[0].terminator
    assert isinstance(branch, ir.Branch) and isinstance(branch.cond, ir.Logic) and branch.cond.op == "and"
    assert isinstance(branch.cond.right, ir.InputMatch) and branch.cond.right.pattern.bits == "XX1"  # user input 3
    then, other = mod.routines[0].block(branch.then), mod.routines[0].block(branch.otherwise)
    assert isinstance(then.ops[0], ir.Call) and isinstance(other.ops[0], ir.Call)
    assert then.terminator.target == other.terminator.target  # both reach the join
    untils = [b.terminator for b in blocks if isinstance(b.terminator, ir.Branch)
              and isinstance(b.terminator.cond, ir.Logic) and b.terminator.cond.op == "or"]
    assert untils and mod.routines[0].block(untils[0].otherwise).ops  # back to the REPEAT body
    assert_well_formed(mod)


def test_goto_terminates_and_keeps_what_follows():
    mod = module("XE1\nXD1\nIF(IN_1)\nXG2\nNIF\nXG2\nD5\nXT\nXE2\nXD2\nNIF\nG\nXT\n")
    seq1 = mod.routine("SEQ1")
    gotos = [b.terminator for b in seq1.blocks if isinstance(b.terminator, ir.GotoRoutine)]
    assert [g.routine for g in gotos] == ["SEQ2", "SEQ2"]
    # dead code kept: the D after XG (SEQ2's G reads the register it may set)
    assert any(isinstance(op, ir.Assign) and op.target.name == "%D*" for op in ops(seq1))
    seq2 = mod.routine("SEQ2")
    assert isinstance(ops(seq2)[0], ir.Native) and ops(seq2)[0].mnemonic == "NIF"  # leading NIF
    assert_well_formed(mod)


def test_motion_units_and_moves():
    mod = module("1A10\n1V5\n1MPA\n1D4000\n1G\n1MPI\n1D-200\n1G\n1H\n1G\n1MC\n1G\n1T0.5\n1TRE_X1\n1TRN_X1\n")
    found = ops(mod.routines[0])
    accel, decel, speed = found[0], found[1], found[2]
    # rev/s^2 and rev/s times the profile's 4000 steps per revolution
    assert (accel.param, accel.axis, accel.value.value, accel.value.unit) == (
        ir.MotionParam.ACCEL, "1", 40000, ir.Unit.STEPS_PER_S2)
    # X150 decelerates at A too (one ramp rate for both)
    assert (decel.param, decel.axis, decel.value) == (ir.MotionParam.DECEL, "1", accel.value)
    assert (speed.param, speed.value.value, speed.value.unit) == (ir.MotionParam.MAX_SPEED, 20000, ir.Unit.STEPS_PER_S)
    moves = [op for op in found if isinstance(op, ir.Move)]
    # D then G; D-200 G; H reverses D: the third G moves +200 (L1828)
    assert [(m.mode, m.targets[0][0], m.targets[0][1].value) for m in moves] == [
        (ir.MoveMode.ABSOLUTE, "1", 4000), (ir.MoveMode.RELATIVE, "1", -200), (ir.MoveMode.RELATIVE, "1", 200)]
    assert all(m.targets[0][1].unit is ir.Unit.STEPS for m in moves)
    assert sum(isinstance(op, ir.WaitMotion) for op in found) == 3  # in MN the next command waits for the move
    slew = next(op for op in found if isinstance(op, ir.Slew))  # G in MC runs in D's direction (L2498)
    assert (slew.axis, slew.direction, slew.velocity) == ("1", 1, None)
    assert not any(isinstance(op, ir.Native) for op in found)  # MPA, MPI, MC and D disappear into the moves
    delay = next(op for op in found if isinstance(op, ir.Delay))
    assert (delay.duration.value, delay.duration.unit) == (0.5, ir.Unit.S)
    waits = [op for op in found if isinstance(op, ir.WaitInput)]
    assert isinstance(waits[0].cond, ir.InputMatch) and isinstance(waits[1].cond, ir.Not)


def test_position_mode_defaults_to_incremental():
    mod = module("D4000\nG\n")  # MPI is the factory default (L2608)
    move = ops(mod.routines[0])[0]
    assert move.mode is ir.MoveMode.RELATIVE and move.targets[0] == (ir.ALL_AXES, ir.Const(4000, ir.Unit.STEPS,
                                                                                        move.targets[0][1].span))


def test_mode_that_depends_on_the_path_keeps_the_g_and_says_so():
    result = check("IF(IN_1)\nMPA\nNIF\nD4000\nG\n")
    assert [d.code for d in result.diagnostics] == ["X142"]
    found = ops(result.analysis.module.routines[0])
    assert [op.mnemonic for op in found if isinstance(op, ir.Native)] == ["MPA", "G"]  # modes kept for the G
    assert not any(isinstance(op, ir.Move) for op in found)


def test_sequence_starts_with_the_modes_of_its_calls():
    mod = module("1MPA\n1XE1\n1XD1\n1D100\n1G\n1XT\n1XR1\n")
    move = next(op for op in ops(mod.routine("SEQ1@1")) if isinstance(op, ir.Move))
    assert move.mode is ir.MoveMode.ABSOLUTE


def test_cur_sets_the_step():
    mod = module("1CUR800\n1D1600\n1G\n1V2\n")
    assert mod.steps_per_rev == 800
    found = ops(mod.routines[0])
    assert found[0].param is ir.MotionParam.RESOLUTION and found[0].value.value == 800
    assert next(op for op in found if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.MAX_SPEED
                ).value.value == 1600


def test_a_second_cur_is_reported():
    result = check("CUR4000\nD4000\nG\nCUR800\n")
    assert [d.code for d in result.diagnostics] == ["X143"]


def test_assignments_are_left_to_right():
    mod = module("VAR4=VAR1-VAR2*VAR3\nVAR8=POS+50000\nVAR1=FUN\n")
    first, second, third = ops(mod.routines[0])
    # (VAR1 - VAR2) * VAR3 (L4638-L4642)
    assert first.value.op == "*" and first.value.left.op == "-"
    assert isinstance(second.value.left, ir.Status) and second.value.left.meaning == "position"
    assert isinstance(third, ir.Native) and third.args[1].name == "FUN"  # the RP240 key: X150's own
    assert {"VAR1", "VAR2", "VAR3", "VAR4", "VAR8"} <= set(mod.variables)


def test_natives_keep_mnemonic_args_form_and_axis():
    mod = module("1XE1\n1XD1\n1BCDG50\n1OUT3L\n1DPC208\n1XT\n")  # L: no neutral output function
    natives = ops(mod.routines[0])
    assert [(n.mnemonic, n.form, n.axis) for n in natives] == [
        ("CDG", "B", "1"), ("OUT", "", "1"), ("DPC", "", "1")]
    assert [a.value for a in natives[1].args] == [3, "L"]
    assert [a.value for a in natives[2].args] == [2, 8]


def test_tx_is_a_print_of_its_text_then_the_variable_in_its_format():
    """TXn,m,p,x sends x, then VARn with p decimals, signed when m is 1 (parker-x150.md
    L4463-L4483: `1TX1,0,3,3V` -> 3V987.123, `1TX1,1,0,2D` -> 2D+987)."""
    mod = module("1XE1\n1XD1\n1TX1,0,3,3V\n1TX1,1,0,2D\n1XT\n")
    prints = [op for op in mod.routines[0].blocks[0].ops if isinstance(op, ir.Print)]
    assert [(p.items[0].value, p.items[1].name, p.formats[1], p.signed) for p in prints] == [
        ("3V", "VAR1", "fixed 3 magnitude", False), ("2D", "VAR1", "fixed 0", True)]


def test_mixed_devices_keep_addresses_on_natives():
    mod = module("1A10\n2A10\n1VAR1=5\n2T1\n1SV\nVAR2=1\n")
    found = ops(mod.routines[0])
    assert mod.routines[0].name == "immediate"
    # each A is an acceleration and the same deceleration
    assert [type(op).__name__ for op in found] == ["SetMotion"] * 4 + ["Native", "Native", "Native", "Assign"]
    assert [op.axis for op in found[:7]] == ["1", "1", "2", "2", "1", "2", "1"]


def test_single_device_stream_uses_neutral_operations():
    mod = module("1VAR1=5\n1T1\n1SV\n1WHEN(IN_1)\n")
    assert mod.routines[0].name == "immediate@1"
    assert [type(op).__name__ for op in ops(mod.routines[0])] == ["Assign", "Delay", "Save", "SetHandler"]


def test_calls_resolve_per_device():
    mod = module("XE5\nXD5\nG\nXT\n2XE6\n2XD6\n2G\n2XT\nXR5\n2XR6\n1XR5\n")
    calls = ops(mod.routines[-1])
    assert isinstance(calls[0], ir.Call) and calls[0].routine == "SEQ5"
    assert isinstance(calls[1], ir.Call) and calls[1].routine == "SEQ6@2"
    # device 1 runs the sequence every device stored: the call keeps its address as a Native
    assert isinstance(calls[2], ir.Native) and calls[2].axis == "1"


def test_variable_targets_stay_native():
    mod = module("VAR2=61\nGOSUB(VAR2)\nXG(VAR2)\n")
    natives = [op for op in ops(mod.routines[0]) if isinstance(op, ir.Native)]
    assert [(n.mnemonic, n.args[0].name) for n in natives] == [("GOSUB", "VAR2"), ("XG", "VAR2")]


def test_errors_still_give_a_well_formed_module():
    mod = module("XE1\nXD1\nL5\nIF(VAR1>=5)\nELSE\nN\nNWHILE\nXD2\nREPEAT\n")
    assert_well_formed(mod)


def test_conditionals_and_loops_of_the_immediate_stream_keep_their_meaning():
    """Issue 8: an IF .. ELSE .. NIF in the stream is a branch (not two unconditional calls), and
    a WHILE is a loop back to its test."""
    mod = module("1XE1\n1XD1\n1T1\n1XT\n1XE2\n1XD2\n1T2\n1XT\n"
                 "IF(IN_1)\n1XR1\nELSE\n1XR2\nNIF\nWHILE(VAR1<5)\nVAR1=VAR1+1\nNWHILE\n")
    stream = next(r for r in mod.routines if r.kind is ir.RoutineKind.IMMEDIATE)
    branches = [b for b in stream.blocks if isinstance(b.terminator, ir.Branch)]
    assert len(branches) == 2
    test_if, test_while = branches
    then, other = stream.block(test_if.terminator.then), stream.block(test_if.terminator.otherwise)
    assert [op.routine for op in then.ops] == ["SEQ1@1"] and [op.routine for op in other.ops] == ["SEQ2@1"]
    body = stream.block(test_while.terminator.then)
    assert isinstance(body.ops[0], ir.Assign) and body.terminator.target == test_while.label  # back to the test


def test_input_patterns_are_neutral_user_inputs_and_dedicated_readings():
    """`IN_X1` tests user input 2: the IR's pattern is `X1` (input n is the n-th character); the
    dedicated group (LMT+ LMT- HOME ..., L3778) becomes readings of their neutral meaning."""
    mod = module("1TRE_X1\n1TRNX1\n1IF(IN1_1X)\n1T1\n1NIF\n")
    waits = [op for b in mod.routines[0].blocks for op in b.ops if isinstance(op, ir.WaitInput)]
    assert isinstance(waits[0].cond, ir.InputMatch) and waits[0].cond.pattern.bits == "X1"
    negated = waits[1].cond
    assert isinstance(negated, ir.Not) and negated.cond == ir.Compare(
        "=", ir.Status("limit_minus", "1", None, negated.cond.left.span), ir.Const(1), negated.cond.span)
    branch = next(b.terminator for b in mod.routines[0].blocks if isinstance(b.terminator, ir.Branch))
    assert isinstance(branch.cond, ir.Logic) and branch.cond.op == "and"
    assert branch.cond.left.left.meaning == "limit_plus" and branch.cond.right.pattern.bits == "1"
    assert_well_formed(mod)


def test_modes_reach_a_sequence_called_in_a_loop_of_a_sequence_defined_later():
    """The modes data flow is optimistic: a sequence not yet reached by any call is analysed once one
    does, so a loop around the call does not lose the modes the stream set (samples/x150/03)."""
    result = check("3XE31\n3XD31\n3D100\n3G\n3XT\n3XE30\n3XD30\n3L3\n3GOSUB31\n3N\n3XT\n3MN\n3MPA\n3XR30\n")
    assert "X142" not in {d.code for d in result.diagnostics}
    moves = [op for _, b in result.analysis.module.blocks() for op in b.ops if isinstance(op, ir.Move)]
    assert [m.mode for m in moves] == [ir.MoveMode.ABSOLUTE]


def test_g_in_mc_before_any_d_runs_forward_from_the_factory_d():
    """D's factory default is 4000 (L810): `MC G` at the start of a stream is a forward slew."""
    result = check("MC\nA10\nV10\nG\nSB\n")
    assert "X142" not in {d.code for d in result.diagnostics}
    ops = [op for _, b in result.analysis.module.blocks() for op in b.ops]
    slews = [op for op in ops if isinstance(op, ir.Slew)]
    assert [s.direction for s in slews] == [1] and any(isinstance(op, ir.Stop) and op.ramp for op in ops)


def test_an_unaddressed_distance_uses_the_one_device_cur():
    """parker-x150.md L742-L745: `1CUR2000`, `D4000` "Set distance to 4000 user steps (2 revs)", `G`
    "move 2 revolutions". On a one-device profile the unaddressed D is device 1's, at its CUR: 4000
    steps at the module's 2000 steps/rev (it was 2000, converted at the profile's CUR4000)."""
    mod = module("1CUR2000\nD4000\nG\n")
    assert mod.steps_per_rev == 2000
    [move] = [op for r in mod.routines for op in ops(r) if isinstance(op, ir.Move)]
    assert [t.value for _, t in move.targets] == [4000]
