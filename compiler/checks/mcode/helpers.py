"""What several MCode checks share: the naming rule of user names, the mnemonics they must not be,
the line limit."""

from __future__ import annotations

from mcc.compiler.checks import Program
from mcc.compiler.mcode.resolve import SHORT_USER_NAME, STRICT_USER_NAME, USER_NAME

# limits.label_rule -> (pattern, what it asks for)
NAME_RULES = {"strict": (STRICT_USER_NAME, "a letter then a letter or digit, exactly two characters"),
              "relaxed": (USER_NAME, "a letter followed by up to two letters or digits"),
              "short": (SHORT_USER_NAME, "a letter, alone or followed by a letter or digit")}


def name_rule(program: Program):
    """(pattern, what it asks for) of the profile's `limits.label_rule`."""
    return NAME_RULES.get(str(program.profile.get("limits.label_rule", "strict")), NAME_RULES["strict"])


def user_names(program: Program):
    """(kind, key, node) of every label and variable, labels first, in the order they were met;
    the `SU` label (the power-up program, L3755) is the device's, not a user name."""
    names = program.lowering.resolver.names
    for kind, table in (("label", names.labels), ("variable", names.variables)):
        for key, node in table.items():
            if not (key == "SU" and kind == "label"):
                yield kind, key, node


def is_mnemonic(program: Program, key: str) -> bool:
    """Whether a user name is an MCode name of the profile's firmware (M104)."""
    cat = program.lowering.cat
    return cat.is_reserved(key, program.profile.firmware) or key in cat.legacy


def line_limit(program: Program) -> int:
    return int(program.profile.get("limits.line_length", 64))
