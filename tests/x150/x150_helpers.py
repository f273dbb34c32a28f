"""Helpers for the X150 tests: check or compile a text without touching the disk."""

from __future__ import annotations

import textwrap

from mcc.compiler import driver, ir, profiles


def src(text: str) -> str:
    return textwrap.dedent(text).lstrip("\n")


def check(text: str, profile: str | None = None):
    prof = profiles.load(profile) if profile else None
    return driver.check_file("program.x150", "x150", prof, text=src(text))


def compile_(text: str, profile: str | None = None):
    prof = profiles.load(profile) if profile else None
    return driver.compile_file("program.x150", "x150", target=None, profile=prof, text=src(text))


def codes(text: str, profile: str | None = None) -> list[str]:
    return sorted(d.code for d in check(text, profile).diagnostics)


def module(text: str) -> ir.Module:
    result = check(text)
    assert result.analysis is not None
    return result.analysis.module


def output(text: str, profile: str | None = None) -> list[str]:
    result = compile_(text, profile)
    assert result.listing is not None, [(d.code, d.message) for d in result.diagnostics]
    return result.listing.text.splitlines()


def assert_well_formed(mod: ir.Module) -> None:
    """Every block ends in a terminator whose targets are blocks of the same routine."""
    for routine in mod.routines:
        labels = {b.label for b in routine.blocks}
        assert len(labels) == len(routine.blocks), routine.name
        for block in routine.blocks:
            assert block.terminator is not None, (routine.name, block.label)
            for target in ir.successors(block.terminator):
                assert target in labels, (routine.name, block.label, target)
