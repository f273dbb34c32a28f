"""Validation by default (issue 23): `mcc compile` simulates what it writes against its source
whenever the output is not the program as written, writes nothing on a difference (S010 on the
source line, exit 1), and `--no-verify` turns that off and says so."""

from __future__ import annotations

from click.testing import CliRunner

from mcc.cli.commands import cli
from mcc.compiler import ir

# lexium-mcode.txt: VM sets the maximum velocity in steps/s, MA an absolute move, H waits for it; VI=10
# keeps the X150 conversion within its start-speed drift (X216: X150 starts moves from standstill)
PROGRAM = "VM=5120\nVI=10\nA=20000\nD=20000\nPG 100\nMA 51200\nH\nO1=1\nE\nPG\n"


def slow_down(module: ir.Module, context) -> int:
    """A wrong optimization: the maximum speed 2 % lower (a unit factor off by 2 %)."""
    for _, block in module.blocks():
        for index, op in enumerate(block.ops):
            if isinstance(op, ir.SetMotion) and op.param is ir.MotionParam.MAX_SPEED:
                block.ops[index] = ir.SetMotion(op.param, op.axis, ir.Const(op.value.value * 0.98, op.value.unit),
                                                op.span)
                return 1
    return 0


def run(args, tmp_path):
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    out = tmp_path / "out.mxt"
    result = CliRunner().invoke(cli, ["compile", str(source), "-o", str(out), *args])
    return result, out


def test_a_wrong_optimization_is_refused_by_default(tmp_path, monkeypatch):
    from mcc.compiler.opt import fold

    monkeypatch.setattr(fold, "run", slow_down)
    result, out = run([], tmp_path)
    assert result.exit_code == 1, result.output
    assert not out.exists()
    assert "S010" in result.output and "p.mxt:6:" in result.output and "MA 51200" in result.output  # the move that arrives late


def test_no_verify_writes_it_and_says_so(tmp_path, monkeypatch):
    from mcc.compiler.opt import fold

    monkeypatch.setattr(fold, "run", slow_down)
    result, out = run(["--no-verify"], tmp_path)
    assert result.exit_code == 0, result.output
    assert out.exists() and "--no-verify" in result.output and "not validated" in result.output


def test_a_program_the_passes_leave_as_written_is_not_simulated(tmp_path, monkeypatch):
    from mcc.sim import verify

    def fail(*args, **kwargs):
        raise AssertionError("simulated although nothing changed")

    monkeypatch.setattr(verify, "check_translation", fail)
    result, out = run(["-O0"], tmp_path)
    assert result.exit_code == 0, result.output
    result, out = run([], tmp_path)  # -O1 removes nothing from this program
    assert result.exit_code == 0, result.output


def test_another_target_is_validated(tmp_path, monkeypatch):
    from mcc.sim import verify

    calls = []
    real = verify.check_translation
    monkeypatch.setattr(verify, "check_translation", lambda *a, **k: calls.append(a[4]) or real(*a, **k))
    result, out = run(["--target", "x150"], tmp_path)
    assert calls == ["x150"], result.output


def test_verify_checks_even_a_plain_respelling(tmp_path, monkeypatch):
    from mcc.sim import verify

    calls = []
    monkeypatch.setattr(verify, "check_translation", lambda *a, **k: calls.append(a[4]) or "")
    result, out = run(["-O0", "--verify"], tmp_path)
    assert result.exit_code == 0 and calls == ["mcode"], result.output


def test_lint_fix_validates_by_default_and_no_verify_says_so(tmp_path, monkeypatch):
    """`lint --fix` rewrites the program, so it is validated unless --no-verify (issue 23). The
    fix here adds `S` after the final PG (lexium-mcode.txt L5269: save to non-volatile memory)."""
    from mcc.sim import verify

    calls = []
    monkeypatch.setattr(verify, "check_translation", lambda *a, **k: calls.append(a[0]) or "")
    source = tmp_path / "p.mxt"
    source.write_text(PROGRAM)
    result = CliRunner().invoke(cli, ["lint", "--fix", "--unsafe-fixes", "--jobs", "1", str(source)])
    assert len(calls) == 1 and source.read_text() != PROGRAM, result.output
    source.write_text(PROGRAM)
    result = CliRunner().invoke(cli, ["lint", "--fix", "--unsafe-fixes", "--no-verify", "--jobs", "1", str(source)])
    assert len(calls) == 1 and "--no-verify" in result.output and source.read_text() != PROGRAM
