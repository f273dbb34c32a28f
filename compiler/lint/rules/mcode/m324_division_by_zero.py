r"""# M324 division-by-zero

A division by the constant 0.

- kind: lint
- default severity: error
- dialects: mcode
- fix available: no
- manual: L1255, L6337-L6356

## What it means

`<quotient target>=<dividend>/<divisor>` divides one value by another (L6337-L6356); the manual
does not say what the device does when the divisor is 0, so a program that divides by the
constant 0 computes nothing it can rely on. mcc reports it as an error, as it does for Arcus
(A309) and X150 (X309): the same rule, written once over the IR (docs/LINT.md). A divisor held in
a variable is not followed; test it before dividing (`BR lbl, R2=0`).

## Bad

```
VA Q1=0
PG 1
LB G1
  Q1=100/0
  PR Q1
  E
PG
```

## Good

```
VA Q1=0
VA R2=4
PG 1
LB G1
  BR G2, R2=0
  Q1=100/R2
LB G2
  PR Q1
  E
PG
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import division_by_zero
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, division_by_zero,
      messages={"division-by-zero": "'{op} 0' divides by zero, which the manual does not define (L6337-L6356): test "
                                    "the divisor first"})
