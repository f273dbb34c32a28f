"""The editor support of Lexium MCode (lsp/editor.py): where labels and conditions are typed, which
commands a program region allows, the MCode rename rules, and the editor model's indexer."""

from __future__ import annotations

import re

from mcc.lsp import catalog_info, model
from mcc.lsp.editor import Editor, Place

PREFIX = r"^\s*[!*^]?(?:[A-Za-z0-9]\s*)??"  # an optional party-mode device name
LABEL = re.compile(  # the label/address of L1764 BP, L1807 BR, L2124 CL, L2156 CP, L2787 EX,
    # L4551 OE=, L5583 TA=, L5609 TC=, L5744 TM=, and after the first argument of L5711 TI,
    # L5776 TP=, L5848 TR=, L5908 TT=
    PREFIX + r"(?:(?:BR|CL|BP|EX|CP)\s+|(?:OE|TA|TC|TM)\s*=\s*|(?:TI\s+|(?:TP|TR|TT)\s*=\s*)[^,]*,\s*)"
    r"[A-Za-z0-9]*$", re.IGNORECASE)
CONDITION = re.compile(PREFIX + r"(?:BR|CL)\s+[^,\s]+\s*,[^,]*$", re.IGNORECASE)  # L1807, L2124
COMMAND_KINDS = ("instruction", "variable", "flag")
COMMAND = re.compile(r"^\s*[!*^]?([A-Za-z]{1,3}[0-9]?)(?:\s+|=)(.*)$")


class MCodeEditor(Editor):
    indexer = "mcc.lsp.mcode_index"
    places = (Place(LABEL, (model.SYMBOL_LABEL,)),
              # a condition after `BR x,`/`CL x,`: variables, flags and inputs (L1807, L2124)
              Place(CONDITION, (model.SYMBOL_VARIABLE,), values=True, outside_comment=True))
    statement_start = re.compile(r"^\s*[!*^]?[A-Za-z]{0,3}$")
    value_kinds = ("variable", "flag", "keyword", "function")
    variables_declared = True  # a variable is defined by its VA
    # the profiles give the steps per revolution at MS=256 (a 1.8° motor); the file's own MS= scales it
    microstep_setting = "MS"
    microstep_reference = 256.0

    def command_place(self, snap, line: int) -> str:
        """"program" inside a PG … PG region, else "immediate"."""
        for routine in snap.index.routines:
            if routine.kind == "program" and routine.span.line <= line + 1 <= routine.span.end_line:
                return "program"
        return "immediate"

    def allows(self, entry, place: str) -> bool:
        """Instructions, variables and flags, where the catalog's `mode` allows them."""
        if entry.kind not in COMMAND_KINDS:
            return False
        mode = entry.get("mode", "both")
        return mode == "both" or mode == place

    def command_before(self, before: str):
        match = COMMAND.match(before)
        if match:
            return catalog_info.lookup("mcode", match.group(1)), match.group(2)
        return None, ""

    def validate_rename(self, snap, symbol: model.Symbol, new: str):
        """A label or variable name under the profile's label rule, not an MCode name, not taken
        (labels and variables share one name table, L537)."""
        from mcc.compiler.mcode import catalog as mcat
        from mcc.compiler.mcode.resolve import STRICT_USER_NAME, USER_NAME
        from mcc.lsp.navigation import RenameError

        relaxed = snap.profile is not None and snap.profile.get("limits.label_rule", "strict") == "relaxed"
        pattern = USER_NAME if relaxed else STRICT_USER_NAME
        if not pattern.match(new):
            rule = "a letter then a letter or digit, exactly two characters" if not relaxed else \
                "a letter followed by up to two letters or digits"
            raise RenameError(f"'{new}' is not a valid MCode {symbol.kind} name ({rule})")
        cat = mcat.load()
        key = new.upper()
        if cat.is_reserved(key) or key in cat.legacy:
            entry = cat.lookup(key) or cat.functions.get(key)
            what = f"the MCode {entry.kind} {key} ({entry.entry.title})" if entry else f"an MCode command ({key})"
            raise RenameError(f"'{new}' is {what}: user names must not be MCode names")
        if symbol.kind == model.SYMBOL_LABEL and key == "SU":
            raise RenameError("SU is the power-up label: a label renamed to SU would run at power-up")
        for kind in (model.SYMBOL_LABEL, model.SYMBOL_VARIABLE):
            other = snap.index.symbols.get(f"{kind}:{key}")
            if other is not None and other.key != symbol.key:
                where = (other.definitions or other.references)[0].line
                raise RenameError(f"{new} is already a {kind} (line {where}); labels and variables share one "
                                  "name table (L537): choose another")
        return f"{symbol.kind}:{key}", lambda old: new


EDITOR = MCodeEditor()
