"""The lint rules of the Arcus Performax standalone language (A3xx): one module per rule,
`a<nnn>_<name>.py`, whose docstring is the rule's page; importing this package registers them all
(`rules.discover`). What several rules share is in helpers.py; A301, A302, A303, A307, A308, A309
and A314 are rules written once over the IR (rules/shared/): their modules give the Arcus page,
words and the hooks for what only Arcus knows.
"""

from mcc.compiler.lint.rules import discover

discover(__name__, __path__)
