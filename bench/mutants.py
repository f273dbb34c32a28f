"""How strong is the oracle? Small wrong changes to the backends and the optimizer, one at a time,
and whether validation notices them (issue 23, "Oracle strength is measured").

    .venv/bin/python bench/mutants.py [--only NAME,...] [--programs TEXT,...] [--generated N] [--jobs J]
                                      [--full] [--list]

Each mutant is one row of `MUTANTS`: a file of the package, a piece of its text that occurs exactly
once, and the wrong text to put there (a flipped comparison, a dropped wait, an off-by-one loop
count, a unit factor off by 2 %, a dropped setting, a flipped move mode, ...). A mutant runs in a
copy of the package (`<tmp>/mcc`, the patched file replaced) in a subprocess, so the mutants never
touch the work tree and the simulator that judges them is the unpatched one.

The corpus: the samples, the clean golden programs of tests/golden and tests/sim/golden, and
`--generated` programs per dialect from tests/codegen_programs.py; each compiled at -O0 -O1 -O2
-Os to mcode, arcus and x150. The unmutated compiler gives the baseline: the compiles that
validate (sim.verify.check_translation) and the text they write. A mutant is **caught** when a
compile that validated in the baseline now ends in a finding (a divergence, an S010 refusal, an
output that does not check, an internal error). It **survives** otherwise; the report says why:
no written program changed on the corpus (the change is not reached, or is equivalent), only
refusals changed, or programs changed and still validated equal (the oracle's weakness). Without
--full a mutant stops at its first catch. Target: at least 95 % caught.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

TARGETS = ("mcode", "arcus", "x150")
LEVELS = ("O0", "O1", "O2", "Os")
EXTENSIONS = {"mcode": ".mxt", "arcus": ".prg", "x150": ".x150"}


@dataclass(frozen=True)
class Mutant:
    name: str
    file: str  # relative to the package root
    old: str  # occurs exactly once in the file
    new: str
    kind: str  # what sort of mistake it models


M, X, A = "backends/mcode.py", "backends/x150/writer.py", "backends/arcus/"
MUTANTS: tuple[Mutant, ...] = (
    # --- MCode backend
    Mutant("mcode-lt-as-le", M, '"<": "<",', '"<": "<=",', "flipped comparison (off-by-one loop)"),
    Mutant("mcode-ne-as-eq", M, '"!=": "<>"', '"!=": "="', "negated comparison"),
    Mutant("mcode-ge-as-gt", M, '">=": ">="', '">=": ">"', "flipped comparison"),
    Mutant("mcode-ma-mr", M, 'name = "MA" if op.mode is ir.MoveMode.ABSOLUTE else "MR"',
           'name = "MR" if op.mode is ir.MoveMode.ABSOLUTE else "MA"', "move mode flipped"),
    Mutant("mcode-drop-wait", M, 'return f"{self.prefix(op.axis)}H"\n', 'return None\n', "dropped wait"),
    Mutant("mcode-delay-2pct", M, "return format_number(int(round(ms)) if not isinstance(ms, int) else ms)",
           "return format_number(int(round(ms * 1.02)))", "unit factor off by 2 % (delay)"),
    Mutant("mcode-speed-2pct", M, "return format_number(round(scaled) if self.foreign else scaled)",
           "return format_number(round(scaled * 1.02))", "unit factor off by 2 % (speeds, accelerations)"),
    Mutant("mcode-accel-decel-swap", M, 'ir.MotionParam.ACCEL: "A", ir.MotionParam.DECEL: "D"',
           'ir.MotionParam.ACCEL: "D", ir.MotionParam.DECEL: "A"', "settings swapped"),
    Mutant("mcode-drop-decel", M, "        name = PARAM_NAMES[op.param]\n",
           "        name = PARAM_NAMES[op.param]\n        if name == \"D\":\n            return None\n",
           "dropped setting"),
    Mutant("mcode-output-index", M, 'return f"O{op.index}={self.expr(op.value)}"',
           'return f"O{op.index % 3 + 1}={self.expr(op.value)}"', "wrong output"),
    Mutant("mcode-position-plus-2", M, "            return format_number(node.value)\n        if isinstance(node, ir.Var):",
           "            return format_number(node.value + 2 if node.unit is ir.Unit.STEPS else node.value)\n"
           "        if isinstance(node, ir.Var):", "position off by two steps"),
    Mutant("mcode-call-as-jump", M, 'return f"CL {target}"', 'return f"BR {target}"', "call written as a jump"),
    Mutant("mcode-print-newline", M, "{'' if op.newline else ';'}", "{';' if op.newline else ''}",
           "print line end flipped"),
    Mutant("mcode-print-text-stripped", M, "        if isinstance(node, ir.Text):\n            return f'\"{node.value}\"'\n"
           "        if isinstance(node, (ir.Compare,",
           "        if isinstance(node, ir.Text):\n            return f'\"{node.value.strip()}\"'\n"
           "        if isinstance(node, (ir.Compare,", "print text with its spaces stripped"),
    # --- X150 backend
    Mutant("x150-mpa-mpi", X, '"MPA" if op.mode is ir.MoveMode.ABSOLUTE else "MPI"',
           '"MPI" if op.mode is ir.MoveMode.ABSOLUTE else "MPA"', "move mode flipped"),
    Mutant("x150-loop-count-plus-1", X, 'else "L" + self.value(count)',
           'else "L" + self.value(ir.Const(count.value + 1) if isinstance(count, ir.Const) else count)',
           "off-by-one loop count"),
    Mutant("x150-delay-2pct", X, "            return number(expr.value / 1000)\n        return self.value(expr)",
           "            return number(expr.value / 1000)\n"
           "        if isinstance(expr, ir.Const) and isinstance(expr.value, (int, float)):\n"
           "            return number(expr.value * 1.02)\n        return self.value(expr)",
           "unit factor off by 2 % (delay)"),
    Mutant("x150-rate-2pct", X, "revs = units.steps_to_revs(expr.value, self.source_spr)",
           "revs = units.steps_to_revs(expr.value, self.source_spr) * 1.02", "unit factor off by 2 % (V, A)"),
    Mutant("x150-output-inverted", X, 'return "X" * (op.index - 1) + str(int(value.value))',
           'return "X" * (op.index - 1) + str(1 - int(value.value))', "output level inverted"),
    # (MQ for every move instead of MN is an equivalent mutant: the writer then adds TRIP for the wait)
    Mutant("x150-drop-trip", X, 'if self.known("move", key) != "MN":',
           'if self.known("move", key) == "MC":', "dropped wait (no TRIP after an MQ move)"),
    Mutant("x150-relation-flipped", X, "terms.append(self.operand(cond.left) + cond.op + self.operand(cond.right))",
           "terms.append(self.operand(cond.left) + {'<': '>', '>': '<'}.get(cond.op, cond.op) + "
           "self.operand(cond.right))", "flipped comparison"),
    Mutant("x150-drop-speed", X, 'self.emit(prefix + "V" + self.rate(op.value, "speed"), span)',
           'self.rate(op.value, "speed")', "dropped setting"),
    Mutant("x150-input-inverted", X, 'terms.append("IN" + bits)',
           'terms.append("IN" + bits.replace("1", "t").replace("0", "1").replace("t", "0"))', "input level inverted"),
    Mutant("x150-plus-minus", X, "text += op + self.operand(right)",
           'text += {"+": "-", "-": "+"}.get(op, op) + self.operand(right)', "arithmetic operator swapped"),
    # --- Arcus backend
    Mutant("arcus-lt-as-le", A + "writer.py", 'return f"{self.text(cond.left)}{cond.op}{self.text(cond.right)}"',
           'return f"{self.text(cond.left)}{ {\'<\': \'<=\'}.get(cond.op, cond.op)}{self.text(cond.right)}"',
           "flipped comparison (off-by-one loop)"),
    Mutant("arcus-abs-inc", A + "move_modes.py", "NEED = {ir.MoveMode.ABSOLUTE: ABS, ir.MoveMode.RELATIVE: INC}",
           "NEED = {ir.MoveMode.ABSOLUTE: INC, ir.MoveMode.RELATIVE: ABS}", "move mode flipped"),
    Mutant("arcus-mode-maybe-in-force", A + "move_modes.py", "if mode is not None and seen.get(where, NONE) != {mode}:",
           "if mode is not None and mode not in seen.get(where, NONE):", "dropped mode switch (may be taken as is)"),
    Mutant("arcus-delay-2pct", A + "convert.py", "return ir.Const(round(units.s_to_ms(value.value))",
           "return ir.Const(round(units.s_to_ms(value.value) * 1.02)", "unit factor off by 2 % (delay)"),
    Mutant("arcus-speed-2pct", A + "convert.py", "max(1, round(units.scale_rate(value.value, self.factor)))",
           "max(1, round(units.scale_rate(value.value, self.factor) * 1.02))", "unit factor off by 2 % (speeds)"),
    Mutant("arcus-drop-wait", A + "writer.py", 'self.bare(self.by_ir["wait_motion"], span, axis=axis)', "pass",
           "dropped wait"),
    Mutant("arcus-plus-minus", A + "writer.py", 'return f"{self.text(value.left)}{value.op}{self.text(value.right)}"',
           'return f"{self.text(value.left)}{ {\'+\': \'-\', \'-\': \'+\'}.get(value.op, value.op)}'
           '{self.text(value.right)}"', "arithmetic operator swapped"),
    Mutant("arcus-gosub-next", A + "writer.py", 'self.add(f"GOSUB {number}"', 'self.add(f"GOSUB {number + 1}"',
           "wrong subroutine called"),
    # --- optimizer
    Mutant("fold-minus-reversed", "compiler/opt/fold.py", "value = values.binary(op, a, b)",
           "value = values.binary(op, b, a) if op == '-' else values.binary(op, a, b)", "constant folded wrong"),
    Mutant("fold-inexact-division", "compiler/opt/fold.py", 'if op == "/" and (b == 0 or a % b != 0):',
           'if op == "/" and b == 0:',
           "division folded with floor instead of refused"),
    Mutant("fold-no-overflow-check", "compiler/opt/fold.py", "    if not INT32[0] <= value <= INT32[1]:\n        return None\n",
           "", "overflow folded without wrapping"),
    Mutant("fold-decide-lt-le", "compiler/opt/fold.py", '"<": a < b', '"<": a <= b', "branch decided wrong"),
    Mutant("fold-call-keeps-values", "compiler/opt/fold.py", "            if clobbers_everything(op):\n                known.clear()",
           "            if isinstance(op, ir.Native):\n                known.clear()", "values kept across a call"),
    Mutant("settings-drop-any-repeat", "compiler/opt/settings.py", "if last.get(slot) == value:",
           "if last.get(slot) is not None:", "dropped setting (a changed value taken as redundant)"),
    Mutant("settings-call-keeps-values", "compiler/opt/settings.py",
           "elif isinstance(op, (ir.Call, ir.Native, ir.Pause)):", "elif isinstance(op, (ir.Native, ir.Pause)):",
           "dropped setting (a call's settings ignored)"),
    # (a move's reads ignored is equivalent: a move ends every pending store anyway, TAKES_TIME)
    Mutant("dead-stores-assign-reads-nothing", "compiler/opt/dead_stores.py", "            for name in reads_of(op):\n",
           "            for name in (reads_of(op) if not isinstance(op, ir.Assign) else ()):\n",
           "a store read by a calculation removed"),
    Mutant("copies-source-reassigned", "compiler/opt/copies.py",
           "copies = {k: v for k, v in copies.items() if k != name and v.name != name}",
           "copies = {k: v for k, v in copies.items() if k != name}", "copy kept after its source changes"),
    Mutant("branches-verdict-swapped", "compiler/opt/branches.py", "ir.Jump(term.then if verdict else term.otherwise",
           "ir.Jump(term.otherwise if verdict else term.then", "constant branch taken the wrong way"),
    Mutant("outline-overlapping-runs", "compiler/opt/outline.py", "if start >= last_end.get(bi, -1):",
           "if start >= last_end.get(bi, -1) - 1:", "overlapping repeated runs outlined (-Os)"),
    Mutant("outline-eats-next-op", "compiler/opt/outline.py", "ops[start:start + length] = [ir.Call(",
           "ops[start:start + length + 1] = [ir.Call(", "outlined run replaces one operation too many (-Os)"),
    # (in the pass, not in opt/common.reached, which the validation's fingerprint shares)
    Mutant("unreachable-first-successor", "compiler/opt/unreachable.py",
           "        seen = reached({b.label: b for b in routine.blocks}, roots)\n",
           "        by_label = {b.label: b for b in routine.blocks}\n        seen, todo = set(), list(roots)\n"
           "        while todo:\n            label = todo.pop()\n"
           "            if label in seen or label not in by_label:\n                continue\n"
           "            seen.add(label)\n"
           "            todo.extend(list(ir.successors(by_label[label].terminator))[:1])\n",
           "reachable blocks removed (only a branch's first target followed)"),
    Mutant("tails-different-ops", "compiler/opt/tails.py", "len({key(s.ops[-1]) for s in sources}) == 1",
           "len({key(s.ops[-1]) for s in sources}) <= 2", "different tails hoisted into the join"),
)


# --------------------------------------------------------------------------------------------
# The corpus and one compile's verdict


def corpus(generated: int) -> list[dict]:
    """Every clean program: samples, golden programs, generated ones (dialect, name, text)."""
    from codegen_programs import DIALECTS, generate
    from mcc.compiler import driver

    programs = []
    for dialect, ext in EXTENSIONS.items():
        files = sorted((ROOT / "samples" / dialect).glob(f"*{ext}"))
        files += sorted((ROOT / "tests" / "golden" / dialect).glob(f"*/*{ext}"))
        files += sorted((ROOT / "tests" / "sim" / "golden" / dialect).glob(f"*{ext}"))
        for path in files:
            text = path.read_text(encoding="utf-8", errors="replace")
            result = driver.check_file(str(path), dialect, None, text)
            if not result.has_errors and result.analysis is not None and result.analysis.module is not None:
                programs.append({"dialect": dialect, "name": str(path.relative_to(ROOT)), "text": text})
    for dialect in DIALECTS:
        for seed in range(generated):
            programs.append({"dialect": dialect, "name": f"generated {dialect} seed {seed}",
                             "text": generate(dialect, seed).text})
    return programs


def verdict(dialect: str, name: str, text: str, target: str, level: str) -> tuple[str, str]:
    """('validated', digest of the written text) | ('refused', codes) | (finding kind, detail)."""
    from mcc.compiler import dialects, driver
    from mcc.sim.verify import check_translation

    path = "corpus" + EXTENSIONS[dialect]
    try:
        result = driver.compile_file(path, dialect, target, None, text, level)
    except Exception as exc:  # noqa: BLE001 - a traceback is a catch
        return "internal", f"{type(exc).__name__}: {exc}"
    if any(d.kind.value == "internal" for d in result.diagnostics):
        return "internal", next(d.message for d in result.diagnostics if d.kind.value == "internal")
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    if any(d.code == "S010" for d in errors):
        return "caught-divergence", next(d.message for d in errors if d.code == "S010")
    if errors or result.listing is None:
        return "refused", ",".join(sorted({d.code for d in errors}))
    try:
        profile = driver.profile_for(dialects.get(target), None)
        problem = check_translation(path, dialect, result.analysis.module, result.listing.text, target, profile)
    except Exception as exc:  # noqa: BLE001
        return "internal", f"validation raised {type(exc).__name__}: {exc}"
    if problem.startswith("the written program has errors"):
        return "bad-output", problem
    if problem:
        return "divergence", problem
    return "validated", hashlib.sha1(result.listing.text.encode()).hexdigest()


def judge(job: dict) -> dict:
    """Run in a worker: the verdict of every compile in `job['compiles']`; with `baseline`, stop at
    the first compile that validated there and does not now (unless `full`)."""
    programs = job["programs"]
    baseline = job.get("baseline")
    out = {"verdicts": {}, "caught": None, "changed": 0, "refusals": 0, "compiles": 0}
    for key in job["compiles"]:
        index, target, level = key.split("|")
        program = programs[int(index)]
        kind, detail = verdict(program["dialect"], program["name"], program["text"], target, level)
        out["compiles"] += 1
        if baseline is None:
            out["verdicts"][key] = [kind, detail]
            continue
        before_kind, before_detail = baseline[key]
        if kind == "validated" and detail != before_detail:
            out["changed"] += 1
        elif kind == "refused":
            out["refusals"] += 1
            out["changed"] += 1
        elif kind != "validated":
            out["caught"] = {"program": program["name"], "target": target, "level": level, "kind": kind,
                             "detail": detail[:400]}
            if not job.get("full"):
                break
    return out


# --------------------------------------------------------------------------------------------
# Running a mutant in a patched copy


def package_copy(tmp: Path) -> Path:
    """The package as `tmp/mcc` without what a compile never reads."""
    target = tmp / "mcc"
    shutil.copytree(ROOT, target, ignore=shutil.ignore_patterns(
        ".venv", ".git", "tests", "docs", "bench", "samples", "editors", "node_modules", "*.egg-info", "__pycache__",
        ".hypothesis", ".pytest_cache"))
    return target


def apply(mutant: Mutant, package: Path) -> None:
    path = package / mutant.file
    text = path.read_text()
    count = text.count(mutant.old)
    if count != 1:
        raise SystemExit(f"mutant {mutant.name}: the text to change occurs {count} times in {mutant.file}, "
                         "not once: the source moved; update the table")
    path.write_text(text.replace(mutant.old, mutant.new))


def run_worker(job: dict, package_parent: Path | None) -> dict:
    """`judge(job)` in a fresh interpreter whose `mcc` is the copy under `package_parent`."""
    env = dict(os.environ)
    if package_parent is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(package_parent), str(ROOT / "tests"), env.get("PYTHONPATH", "")])
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as handle:
        json.dump(job, handle)
        job_file = handle.name
    code = ("import json, sys; sys.path.insert(0, sys.argv[2]); import mutants; "
            "print(json.dumps(mutants.judge(json.load(open(sys.argv[1])))))")
    done = subprocess.run([sys.executable, "-c", code, job_file, str(ROOT / "bench")], capture_output=True, text=True,
                          env=env, cwd=str(package_parent or ROOT), timeout=3600)
    os.unlink(job_file)
    if done.returncode != 0:
        return {"verdicts": {}, "caught": {"program": "-", "target": "-", "level": "-", "kind": "crash",
                                           "detail": done.stderr.strip().splitlines()[-1] if done.stderr else "?"},
                "changed": 0, "refusals": 0, "compiles": 0}
    return json.loads(done.stdout.strip().splitlines()[-1])


def check_mcc_is_the_copy(package_parent: Path) -> None:
    env = dict(os.environ, PYTHONPATH=str(package_parent))
    where = subprocess.run([sys.executable, "-c", "import mcc; print(mcc.__file__)"], capture_output=True, text=True,
                           env=env, cwd=str(package_parent)).stdout.strip()
    if not where.startswith(str(package_parent)):
        raise SystemExit(f"the patched copy is not the mcc a worker imports ({where}); cannot run mutants")


def mutant_job(mutant: Mutant, job: dict) -> tuple[Mutant, dict, float]:
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="mcc-mutant-") as tmp:
        package = package_copy(Path(tmp))
        apply(mutant, package)
        check_mcc_is_the_copy(Path(tmp))
        result = run_worker(job, Path(tmp))
    return mutant, result, time.monotonic() - start


def survivor_reason(result: dict) -> str:
    if result["changed"] == 0:
        return "no written program changed on the corpus: the mutated code is not reached, or the change is equivalent"
    if result["refusals"] == result["changed"]:
        return f"it only makes {result['refusals']} compiles refuse (a refusal is not wrong code)"
    return (f"{result['changed'] - result['refusals']} written programs changed and still validated equal: "
            "the comparison's tolerance or scenarios do not see the difference")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", help="comma-separated mutant names")
    parser.add_argument("--generated", type=int, default=20, help="generated programs per dialect in the corpus")
    parser.add_argument("--programs", help="comma-separated texts: keep only the corpus programs whose name holds "
                                           "one (while developing; the figure is the whole corpus's)")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--full", action="store_true", help="run the whole corpus for every mutant")
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    args = parser.parse_args(argv)
    mutants = [m for m in MUTANTS if not args.only or m.name in args.only.split(",")]
    if args.list:
        for m in mutants:
            print(f"{m.name:34s} {m.file:30s} {m.kind}")
        return 0
    with tempfile.TemporaryDirectory() as tmp:  # every mutant applies to today's source, before anything runs
        package = package_copy(Path(tmp))
        for mutant in mutants:
            apply(mutant, package)

    start = time.monotonic()
    programs = corpus(args.generated)
    if args.programs:
        wanted = args.programs.split(",")
        programs = [p for p in programs if any(w in p["name"] for w in wanted)]
    compiles = [f"{i}|{t}|{lvl}" for i in range(len(programs)) for t in TARGETS for lvl in LEVELS]
    base = run_worker({"programs": programs, "compiles": compiles}, None)["verdicts"]
    validated = [k for k in compiles if base.get(k, ["?"])[0] == "validated"]
    print(f"corpus: {len(programs)} programs, {len(compiles)} compiles, {len(validated)} validate unmutated "
          f"(the others are refused or are findings already); baseline {time.monotonic() - start:.0f} s", flush=True)
    job = {"programs": programs, "compiles": validated, "baseline": base, "full": args.full}

    caught, survivors = [], []
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for mutant, result, seconds in pool.map(lambda m: mutant_job(m, job), mutants):
            hit = result["caught"]
            if hit:
                caught.append(mutant)
                print(f"caught   {mutant.name:34s} {seconds:5.0f} s  {hit['kind']}: {hit['program']} -> "
                      f"{hit['target']} -{hit['level']}: {hit['detail'][:160]}", flush=True)
            else:
                survivors.append((mutant, survivor_reason(result)))
                print(f"SURVIVED {mutant.name:34s} {seconds:5.0f} s  {survivor_reason(result)}", flush=True)
    share = len(caught) / len(mutants) if mutants else 1.0
    print(f"\n{len(caught)} of {len(mutants)} mutants caught ({share:.0%}); target 95 %; "
          f"{time.monotonic() - start:.0f} s in all")
    for mutant, reason in survivors:
        print(f"  survivor {mutant.name} ({mutant.kind}, {mutant.file}): {reason}")
    return 0 if share >= 0.95 else 1


if __name__ == "__main__":
    sys.exit(main())
