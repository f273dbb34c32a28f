"""Lint rules written once over the IR, for every dialect that has them (docs/LINT.md).

A position read while a move may still run, a move before its speeds are set, a loop that only
spins, a division by the constant 0, motion nothing ever stops, code that can never run, a
variable nothing reads, a subroutine nothing calls, a variable read before it is written: each
means the same whatever the dialect, so each is one module here (`NAME`, and a function over the
IR's neutral operations, the CFG and the data flow of `flow.py`, and the file's symbol table and
def-use chains, `Analysis.symbols`, `.defuse`).

What stays per dialect is one module in the dialect's package per shared rule it has (M301,
A301, ...): the rule's page as its docstring and a `speak(__name__, <shared rule>, ...)` call that
gives the rule's messages in the dialect's words, the options that differ by dialect and the hooks
only the dialect knows (voice.py). A dialect that has no module for a shared rule does not run it.

This package holds no rule of its own: `rules.load` never imports it, a dialect's rule imports the
shared rule it speaks.
"""
