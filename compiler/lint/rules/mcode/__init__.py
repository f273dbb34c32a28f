"""The lint rules of Lexium MCode (M3xx): one module per rule, `m<nnn>_<name>.py`, whose docstring is
the rule's page; importing this package registers them all (`rules.discover`).

Rules work on the IR where the question is about behaviour (flow, trips, calls) and on the syntax
tree where it is about how something is written (`=<`, argument order, the last line). Facts about
commands come from the catalog (trip bits, float registers), never from tables written here; what
several rules share is in helpers.py. M301, M306, M307, M313 and M324 are rules written once over
the IR (rules/shared/): their modules give the MCode page and words.

M323 (the program runs on into a subroutine) is a check of the frontend since issue 12, so that
`mcc check` reports it too: compiler/checks/mcode/m323_falls_into_subroutine.py.
"""

from mcc.compiler.lint.rules import discover

discover(__name__, __path__)
