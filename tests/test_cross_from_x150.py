"""X150 programs converted to MCode and to the Arcus PMX-4EX-SA (issue 24).

Each conversion is written after the manuals' examples and validated in the simulator (the
compile's `--verify`: a difference would be S010 and nothing written). Each test cites the lines of
both manuals that make the two programs do the same thing."""

from __future__ import annotations

from mcc.compiler import driver
from mcc.sim.interpreter import simulate


def compile_x150(text: str, target: str):
    return driver.compile_file("p.x150", "x150", target, text=text)


def errors(result) -> list:
    return [(d.code, d.span.line, d.message) for d in result.diagnostics if d.severity.value == "error"]


def prints(dialect: str, text: str, name: str) -> list[str]:
    result = driver.check_file(name, dialect, text=text)
    assert result.analysis is not None, errors(result)
    return [printed for _, printed in simulate(result.analysis.module, profile=result.profile).prints]


# -- the position report into MCode ---------------------------------------------------------------

def test_a_position_report_becomes_a_branch_that_prints_the_plus():
    """parker-x150.md L3141-L3143: `1PR` answers `*` and the position "preceded by a sign"
    (`*-25600`; `*+4000` for a positive one, docs/dialects/x150.md). lexium-mcode.txt L4880-L4906:
    MCode's PR prints text and values, a negative number with its `-`, a positive one bare, and
    ends the line unless `;`. So the output reads the position once into a variable and prints
    `"*+",Z0` or `"*",Z0` by a BR on its sign (BR is a program statement, L1127, M112: the stream
    becomes the program). Validated: the simulator prints the same characters on both sides."""
    source = "1A10\n1V5\n1D-2000\n1G\n1PR\n1D6000\n1G\n1PR\n"
    result = compile_x150(source, "mcode")
    assert not errors(result), errors(result)
    text = result.listing.text
    assert 'PR "*+",' in text and 'PR "*",' in text and "BR " in text
    assert prints("mcode", text, "out.mxt") == prints("x150", source, "p.x150") == ["*-2000\n", "*+4000\n"]


def test_a_report_in_the_source_steps_where_the_output_counts_finer():
    """The X150 counts 4000 user steps/rev here (CUR default, parker-x150.md L735); no MCode MS
    gives 4000 (lexium-mcode.txt L4282-L4340), and a distance computed at run time asks for a
    whole multiple: MS=100, 20000 steps/rev, 5 per X150 step. The report divides the drive's P by
    5, which is exact: every position the output moves to is a multiple of 5 (`MR Z0` with Z0 in
    the drive's steps, docs/CROSS.md "Steps in variables")."""
    source = "XE5\nXD5\nA2\nV5\nD25000\nGOSUB2\nD50000\nGOSUB2\nXT\nXE2\nXD2\nG\n1PR\nXT\nXR5\n"
    result = compile_x150(source, "mcode")
    assert not errors(result), errors(result)
    text = result.listing.text
    assert "MS=100" in text and "=P/5" in text
    assert prints("mcode", text, "out.mxt") == ["*+25000\n", "*+75000\n"]


def test_a_report_after_a_homing_or_a_slew_at_another_resolution_is_refused():
    """A homing stops where the switch is found (parker-x150.md L1711-L1734; lexium-mcode.txt
    L3198-L3210), and a slew where its stop ramp ends, possibly between two X150 steps of the finer
    MCode count: P/5 would round where the X150's own counter holds a whole step. Refused on the
    report's line, naming the profile way out."""
    result = compile_x150("XE1\nXD1\nGH+2\nVAR1=500\nD(VAR1)\nG\n1PR\nXT\nXR1\n", "mcode")
    found = [e for e in errors(result) if e[0] == "G003" and "position report" in e[2]]
    assert [e[1] for e in found] == [7]
    # a run at a velocity stopped by S (L3667-L3674) stops where the ramp ends, not on a source step
    result = compile_x150("MC\nA10\nV10\nG\nS\nVAR1=500\nMN\nD(VAR1)\nG\n1PR\n", "mcode")
    found = [e for e in errors(result) if e[0] == "G003" and "position report" in e[2]]
    assert [e[1] for e in found] == [10], errors(result)


def test_a_variable_holding_a_distance_in_steps_is_not_scaled_twice():
    """parker-x150.md L1349 (D sets the distance; GOSUB L1759-L1776 runs it from another
    sequence): `D25000` is the distance register set to 25000 X150 steps. At MS=100 the output
    writes it `Z0=125000` (5 drive steps per X150 step) and moves `MR Z0` (lexium-mcode.txt MR):
    multiplying again at the move (`MR Z0*5`) would go five times as far."""
    source = "XE5\nXD5\nA2\nV5\nD25000\nGOSUB2\nD50000\nGOSUB2\nXT\nXE2\nXD2\nG\nXT\nXR5\n"
    result = compile_x150(source, "mcode")
    assert not errors(result), errors(result)
    lines = result.listing.text.splitlines()
    assert "MS=100" in lines and "Z0=125000" in lines and "MR Z0" in lines


def test_a_sum_of_a_position_and_a_plain_number_reads_the_position_in_the_source_steps():
    """parker-x150.md L4622-L4629: `VAR8=POS+50000` adds the position counter (in X150 steps) to a
    number. Where the output counts 5 drive steps per X150 step, P counts drive steps and the
    number does not: the output reads `P/5` (exact, every position it moves to is a multiple of 5),
    first, since MCode evaluates left to right (lexium-mcode.txt L1249; docs/dialects/mcode.md):
    `Z0=P/5+50000`. With the number first (`50000+POS`) that division would apply to the sum:
    refused on its line (G003)."""
    result = compile_x150("VAR8=POS+50000\nD(VAR8)\nG\nD4000\nG\n", "mcode")
    assert not errors(result), errors(result)
    assert any(line.endswith("=P/5+50000") for line in result.listing.text.splitlines())
    lines = result.listing.text.splitlines()
    assert "Z1=4000" in lines  # the distance register holds X150 steps here (D(VAR8)): D4000 as written
    result = compile_x150("VAR8=50000+POS\nD(VAR8)\nG\n", "mcode")
    assert 1 in [e[1] for e in errors(result) if "plain number" in e[2]]


def test_a_sequence_reached_by_goto_runs_once():
    """parker-x150.md L1788: GOTO "transfers program control to a designated sequence" (the GOTO
    example, L1801-L1816: XR5 runs sequence 5, which goes to sequence 2, which moves and reports).
    Sequence 2 is not a main program of its own: the X150 runs it once, when sequence 5 gets there.
    The simulator moved it a second time before (it took the unreached-by-call sequence for the
    main routine); the MCode output (`CL`, then its `RT`) moves once too."""
    source = "XE5\nXD5\nA2\nV5\nD25000\nGOTO2\nXT\nXE2\nXD2\nG\n1PR\nXT\nXR5\n"
    assert prints("x150", source, "p.x150") == ["*+25000\n"]
    result = compile_x150(source, "mcode")
    assert not errors(result), errors(result)
    assert prints("mcode", result.listing.text, "out.mxt") == ["*+25000\n"]


# -- drive set-up the target has no panel for ------------------------------------------------------

def test_panel_key_enables_are_left_out_where_there_is_no_panel():
    """parker-x150.md L860-L885 (DCNT: the RP240's PAUSE and CONTINUE keys) and L1237-L1253
    (DSTP: its STOP key); the DCNT example L889-L896. Neither the Lexium drive (lexium-mcode.txt
    has no operator panel: its I/O is IS/OS, L6936ff.) nor the PMX-4EX-SA (arcus-pmx-4ex-sa.txt:
    DI1-DI8 and the host, no keypad) has such keys, so no key press can pause or stop the
    converted program: the settings are left out with warning G051 and listed at the top
    (docs/decisions/0016-drive-setup-dropped.md)."""
    source = "1XE10\n1XD10\n1DCNT1\n1DSTP1\n1XT\n"
    for target in ("mcode", "arcus"):
        result = compile_x150(source, target)
        assert not errors(result), errors(result)
        assert sorted(d.span.line for d in result.diagnostics if d.code == "G051") == [3, 4]
        assert "panel_pause_keys" in result.listing.text and "panel_stop_key" in result.listing.text


# -- S / STOP: a stop on receipt --------------------------------------------------------------------

def test_a_stop_sent_while_nothing_waits_is_a_stop_with_deceleration():
    """parker-x150.md L3667-L3674 (the S example: MC A10 V10 G S, "the motor will decelerate to a
    stop at a rate of 10 revs/sec/sec as soon as S is entered"), STOP L4050-L4070 the same. S acts
    on receipt and clears the buffer, which here holds nothing (MC's G does not wait, L2498):
    the stop comes in its turn, like SB (L3694). MCode: `SL 0` decelerates the slew to a stop
    at D (lexium-mcode.txt SL, L5393ff.); Arcus: `STOP` decelerates every axis to a stop
    (arcus-pmx-4ex-sa.txt L696, L1661)."""
    for mnemonic in ("S", "STOP"):
        source = f"MC\nA10\nV10\nG\n{mnemonic}\n"
        to_mcode = compile_x150(source, "mcode")
        assert not errors(to_mcode), errors(to_mcode)
        assert to_mcode.listing.text.splitlines()[-2:] == ["SL VM", "SL 0"]
        to_arcus = compile_x150(source, "arcus")
        assert not errors(to_arcus), errors(to_arcus)
        assert "STOP" in to_arcus.listing.text.splitlines()


def test_a_stop_that_may_arrive_before_its_turn_stays_refused():
    """parker-x150.md L3660-L3664: S ends the move in progress and clears the buffer on receipt.
    After an MN move (`G` waits for its end, L2522-L2529) or a delay, the S the host sends at once
    would stop that move and clear what follows; a stop in its turn would not: refused at its line
    in both targets."""
    for source in ("A10\nV10\nD8000\nG\nS\n", "T2\nMC\nA10\nV10\nG\nS\n"):
        lines = source.count("\n")
        for target in ("mcode", "arcus"):
            result = compile_x150(source, target)
            assert lines in [e[1] for e in errors(result) if e[0] == "G003"], errors(result)


# -- Y: a loop ended at the end of the pass under way -------------------------------------------------

def test_a_loop_that_y_ends_at_once_runs_one_pass():
    """parker-x150.md L5484-L5506: Y is immediate and "terminates a loop at end of the current pass";
    in its example (`L A10 V10 D8000 T2 G N Y`) the host sends Y right after N, during the first
    pass (T2 waits 2 s, L4101ff.), so the loop runs once. The IR's loop counts one pass; MCode
    writes the counter and `DC`/`BR` (lexium-mcode.txt L2325, L1779), Arcus a WHILE on a
    variable (arcus-pmx-4ex-sa.txt L2109-L2117). One move of 8000 X150 steps on both sides."""
    source = "L\nA10\nV10\nD8000\nT2\nG\nN\nY\n"
    check = driver.check_file("p.x150", "x150", text=source)
    trace = simulate(check.analysis.module, profile=check.profile)
    assert trace.stopped == "end" and [e.data["to"] for e in trace.events if e.kind == "move"] == [{"1": 8000}]
    for target in ("mcode", "arcus"):
        result = compile_x150(source, target)
        assert not errors(result), errors(result)


def test_a_y_that_may_arrive_in_another_pass_stays_refused():
    """parker-x150.md L5497: Y ends the pass "during which the Y command is entered". After a delay
    sent before the loop (T1, L4101ff.) the Y arrives before the loop starts; in a loop that never
    waits it arrives after an unknown number of passes: refused at its line."""
    for source in ("T1\nL\nA10\nV10\nD8000\nG\nN\nY\n", "L\nO1\nO0\nN\nY\n"):
        result = compile_x150(source, "mcode")
        assert source.count("\n") in [e[1] for e in errors(result) if e[0] == "G003"], errors(result)


# -- calls of sequences the file does not define -----------------------------------------------------

def test_a_call_of_a_sequence_stored_on_the_controller_says_to_add_it_to_the_file():
    """parker-x150.md L5125ff. (XR runs a stored sequence; the WHILE examples, L2711-L2730, call
    sequences they do not define): the sequence is on the X150, not in the file, so the converted
    program (MCode `CL` to a label of the program, lexium-mcode.txt L2106; Arcus `GOSUB n` to a
    `SUB n` of the same program, arcus-pmx-4ex-sa.txt L2176-L2192) has nothing to call. Refused at the call's line, telling the
    user to add the definition to the file."""
    source = "VAR1=0\nWHILE(VAR1<5)\nXR1\nVAR1=VAR1+1\nNWHILE\n"
    for target in ("mcode", "arcus"):
        found = [e for e in errors(compile_x150(source, target)) if e[1] == 3]
        assert found and "add the definition of SEQ1 to the file" in found[0][2], found


# -- a resolution that names the source's own steps ------------------------------------------------

def test_a_cur_in_the_programs_own_steps_is_written_as_nothing_and_a_second_one_refused():
    """parker-x150.md L731-L747: CUR sets the user steps per revolution, the unit of D (the
    motor's travel per revolution is unchanged); the IR counts in the program's CUR. MCode counts in
    MS x 200 steps/rev (lexium-mcode.txt L4282-L4340), a code list without 4000: the output never
    writes `MS=20` (no such code) but converts the positions into the steps it uses. A second CUR
    changes the unit of what follows (X143): refused at its line."""
    result = compile_x150("1CUR4000\nA10\nV5\nD4000\nG\n", "mcode")
    assert not errors(result), errors(result)
    assert "MS=20" not in result.listing.text and "MR 51200" in result.listing.text
    result = compile_x150("1CUR4000\n1D4000\n1CUR2000\n", "mcode")
    assert [e[1] for e in errors(result)] == [3]


# -- QS: the identity of the device ---------------------------------------------------------------

def test_the_identity_report_prints_the_address_of_the_device_the_drive_stands_for():
    """parker-x150.md L3207-L3217: QS "responds with the identity of the echoing device": `;*`,
    its address in two digits, `!` (`;*01!` for device 1). The MCode drive stands for device 1 (the
    source profile's first, the one universal commands reach, as the simulator takes it): its PR
    sends the same characters as text (lexium-mcode.txt L4880-L4906: quoted text is printed as it
    is). Validated: both runs print `;*01!`."""
    source = "MN\nD4000\nA100\nV50\nG\nQS\n"
    result = compile_x150(source, "mcode")
    assert not errors(result), errors(result)
    assert 'PR ";*01!"' in result.listing.text.splitlines()
    assert prints("x150", source, "p.x150") == [";*01!\n"]


# -- IV: a speed change that acts on receipt ------------------------------------------------------

def test_an_iv_sent_during_a_move_is_not_a_speed_change_after_it():
    """parker-x150.md L2192-L2216: IV is immediate, "during motion, the speed the motor is travelling
    can be altered"; its example sends `IV20` after an MN `G` (which waits for the move's end in
    the buffer, L2522-L2529): the X150 speeds the move up. Written in its turn (Arcus `SSPDX` after
    the move: "on-the-fly speed change", arcus-pmx-4ex-sa.txt L512) it would change nothing: the IV stays the X150's own
    command there and is refused at its line. Sent while a jog runs (MC `G`, L2498) receipt is its
    turn: the speed change converts (Arcus `SSPDX=`), validated."""
    result = compile_x150("MN\nMPA\nV5\nD-140000\nG\nIV20\n", "arcus")
    assert 6 in [e[1] for e in errors(result) if e[0] == "G003"]
    result = compile_x150("MC\nA10\nV10\nG\nIV20\n", "arcus")
    assert not errors(result), errors(result)
    assert "SSPDX=80000" in result.listing.text.splitlines()


# -- a constant a 32-bit variable cannot hold ------------------------------------------------------

def test_a_constant_beyond_32_bits_is_refused_at_its_line():
    """parker-x150.md L4569-L4573: an X150 variable holds a decimal; MCode's user variables
    (lexium-mcode.txt L1249, VA) and the PMX-4EX-SA's V1-V100 are 32-bit whole numbers, which wrap.
    `VAR4=46341+2147483000` (the fuzz finding of docs/CROSS.md) is 2147529341 on the X150 and a
    negative number on the targets: refused at its line (G003) instead of by the validation."""
    source = "VAR4=46341+2147483000\nIF(VAR4>34)\nO1\nNIF\n"
    for target in ("mcode", "arcus"):
        found = [e for e in errors(compile_x150(source, target)) if e[1] == 1]
        assert found and found[0][0] == "G003" and "2147529341" in found[0][2], found
