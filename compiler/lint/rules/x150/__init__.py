"""The lint rules of the Parker/Digiplan X150 command language (X3xx): one module per rule,
`x<nnn>_<name>.py`, whose docstring is the rule's page; importing this package registers them all
(`rules.discover`). What several rules share is in helpers.py; X301, X303, X307 and X309 are rules
written once over the IR (rules/shared/): their modules give the X150 page, words and the hooks
for what only X150 knows.
"""

from mcc.compiler.lint.rules import discover

discover(__name__, __path__)
