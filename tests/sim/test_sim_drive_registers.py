"""MCode drive registers as neutral settings and readings (docs/SIMULATOR.md, "Drive registers"):
the simulator prints the factory default or the value the program set, trigonometry follows RA,
floats print in the PF format, and the MCode backend writes each register back as it was."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import driver, ir, ir_verify
from mcc.compiler.profiles import load as load_profile
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.programs import module_of
from mcc.sim.files import simulate_file


def prints(tmp_path: Path, program: str, profile=None) -> list[str]:
    path = tmp_path / "prog.mxt"
    path.write_text(program.strip() + "\n")
    trace = simulate_file(str(path), "mcode", profile=profile).trace
    assert trace is not None
    return [line for _t, text in trace.prints for line in text.splitlines()]


def device_replies(*commands: str) -> list[str]:
    device = MCodeDevice()
    out = []
    for command in commands:
        reply = device.command(command.encode() + b"\r").decode("latin-1")
        out += [line for line in reply.replace("\r\n", "\n").split("\n")
                if line and line not in (">", "?") and line != command]
    return out


def test_a_register_reads_its_factory_default_then_the_value_set(tmp_path):
    """CW's factory default is 10 (lexium-mcode.txt L2171-L2200); CW=100 then PR CW prints 100 (L2191)."""
    assert prints(tmp_path, "PR CW\nCW=100\nPR CW") == ["10", "100"]


def test_a_time_register_reads_back_in_milliseconds(tmp_path):
    """D2=50 sets input 2's filter to 50 ms; PR D2 prints 50 (L2221); MT's default is 500 ms (L4341-L4378)."""
    assert prints(tmp_path, "D2=50\nPR D2\nPR MT") == ["50", "500"]


def test_the_print_format_applies_to_float_registers(tmp_path):
    """PR PF prints 10,6,0,0; F1 prints 0.000000; after PF=8,4,1,1 it prints 0.0000E+00 (L4762-L4768)."""
    assert prints(tmp_path, "PR PF\nPR F1\nPF=8,4,1,1\nPR PF\nPR F1") == ["10,6,0,0", "0.000000", "8,4,1,1",
                                                                           "0.0000E+00"]


def test_trigonometry_runs_in_radians_until_ra_selects_degrees(tmp_path):
    """RA's default is radians (L5107): SI of 51200 is -0.994358 (L6685); RA=0 selects degrees (L5106, L5114-L5115)."""
    program = "VA Q1=51200\nF1=SI Q1\nPR F1\nRA=0\nQ1=30\nF1=SI Q1\nPR F1\nPR RA"
    assert prints(tmp_path, program) == ["-0.994358", "0.500000", "0"]


def test_lo_is_the_natural_logarithm_its_example_prints(tmp_path):
    """LO of 51200 prints 10.843495 = ln 51200 (L6636), though the section's title says base 2 (L6618)."""
    assert prints(tmp_path, "VA Q1=51200\nF1=LO Q1\nPR F1") == ["10.843495"]


def test_a_profile_may_take_lo_as_the_base_its_title_says(tmp_path):
    """`[mcode] lo_function = "log2"`: LO is the logarithm base 2 the section's title says (L6618)."""
    custom = tmp_path / "lo2.toml"
    custom.write_text('extends = "lmd-c"\nname = "lo2"\n[mcode]\nlo_function = "log2"\n')
    assert prints(tmp_path, "VA Q1=1024\nF1=LO Q1\nPR F1", load_profile(str(custom))) == ["10.000000"]


def test_pi_is_the_manual_s_constant(tmp_path):
    """PI holds 3.141592654 (L6658): 51200*PI prints 160849.543885 (L6676)."""
    assert prints(tmp_path, "VA Q1=51200\nF1=Q1*PI\nPR F1") == ["160849.543885"]


def test_md_prints_the_last_move_kind(tmp_path):
    """PR MD prints MA after an absolute move (L4145-L4153)."""
    assert prints(tmp_path, "MA 51200\nPR MD") == ["MA"]


def test_ms_reads_back_as_microsteps_per_full_step(tmp_path):
    """MS=4 then PR MS prints 4 (L4330)."""
    assert prints(tmp_path, "MS=4\nPR MS") == ["4"]


@pytest.mark.parametrize("program", ["CW=100\nPR CW", "D2=50\nPR D2", "PF=8,4,1,1\nPR PF", "RA=0\nPR RA",
                                     "MS=4\nPR MS", "TE=127\nPR TE", "LT=50\nPR LT"])
def test_registers_lower_to_neutral_ir_and_compile_back(tmp_path, program):
    """The IR holds no MCode spelling (docs/IR.md, the contract) and the MCode backend writes each
    register back as the source did (L2191, L2221, L4766, L5115, L4330, L5686, L4074)."""
    module = module_of("mcode", program + "\n")
    assert module is not None and ir_verify.verify(module) == []
    assert not any(isinstance(op, ir.Native) for _r, block in module.blocks() for op in block.ops)
    path = tmp_path / "prog.mxt"
    path.write_text(program + "\n")
    result = driver.compile_file(str(path), "mcode", target="mcode")
    assert not result.has_errors, result.diagnostics
    assert [line.text for line in result.listing.lines] == program.splitlines()


def test_the_virtual_device_prints_floats_in_the_pf_format():
    """The device answers PR F1 as the simulator prints it: 1.200000 for F1=Q2/Q1 (L6348-L6355),
    0.0000E+00 under PF=8,4,1,1 (L4768), and trigonometry in radians (L6592)."""
    assert device_replies("VA Q1=25", "VA Q2=30", "F1=Q2/Q1", "PR F1") == ["1.200000"]
    assert device_replies("PF=8,4,1,1", "PR F1") == ["0.0000E+00"]
    assert device_replies("VA Q1=51200", "F1=CS Q1", "PR F1") == ["-0.106072"]


def test_the_virtual_device_keeps_settings_between_commands():
    """An immediate RA=0 holds for the commands after it, as on the drive (RA is Program/Immediate, L5100)."""
    assert device_replies("RA=0", "VA Q1=30", "F1=SI Q1", "PR F1") == ["0.500000"]


def test_pr_os_lists_every_output_setup(tmp_path):
    """PR OS answers every output's type and active level; OS=3,29 keeps output 3's level (L4644-L4650)."""
    assert prints(tmp_path, "OS=1,17,1\nOS=3,29\nPR OS") == ["OS = 1, 17, 1", "OS = 2, 16, 0", "OS = 3, 29, 0"]


def test_pr_ls_lists_both_software_limits(tmp_path):
    """PR LS answers the minus and the plus limit (L4041-L4044)."""
    assert prints(tmp_path, "LS=0,-102400,1\nLS=1,102400,1\nPR LS") == ["LS=0, -102400, 1", "LS=1, 102400, 1"]


def test_pr_uv_lists_the_user_variables(tmp_path):
    """PR UV lists each user variable with G (global) and its value (L5972)."""
    assert prints(tmp_path, "VA Q1=25\nPR UV") == ["Q1 = G 25"]


@pytest.mark.parametrize("program", ["OS=1,17,1\nOS=3,29\nPR OS", "LS=0,-102400,1\nLS=1,102400,1\nPR LS"])
def test_tables_compile_back(tmp_path, program):
    """The setup tables are written back as the source wrote them (L4644-L4646, L4041-L4044)."""
    path = tmp_path / "prog.mxt"
    path.write_text(program + "\n")
    result = driver.compile_file(str(path), "mcode", target="mcode")
    assert not result.has_errors, result.diagnostics
    assert [line.text for line in result.listing.lines] == program.splitlines()


def test_the_virtual_device_and_its_programs_share_the_registers():
    """A register the host sets is what a stored program reads, and one a program sets is what the
    host reads (one drive, L2171-L2200, L4054-L4083): the device's table and the simulator's agree."""
    assert device_replies("PG 100", "PR CW", "LT=60", "E", "PG", "CW=100", "EX 100", "PR LT") == ["100", "60"]
