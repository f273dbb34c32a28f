r"""# X309 division-by-zero

A variable is divided by the constant 0.

- kind: lint
- default severity: error
- dialects: x150
- fix available: no
- manual: L4569-L4643

## What it means

Variable arithmetic has `+ - * /` (L4617-L4620); the manual does not say what a division by zero
gives, and no value is right. Test the divisor first.

## Bad

```
1VAR2=VAR1/0
```

## Good

```
1VAR2=VAR1/4
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import division_by_zero
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, division_by_zero,
      messages={"division-by-zero": "division by zero: the result is undefined"})
