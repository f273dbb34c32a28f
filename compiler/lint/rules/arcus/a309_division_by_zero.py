r"""# A309 division-by-zero

A division or modulus by the constant 0.

- kind: lint
- default severity: error
- dialects: arcus
- fix available: no
- manual: L2669-L2698

## What it means

`/` and `%` are integer operations of the assignment statement (L2681-L2691); the manual does not
say what the controller does when the divisor is 0, and no result is right. Test the divisor before
dividing.

## Bad

```
V1=100
V2=V1/0
END
```

## Good

```
V1=100
V3=4
IF V3!=0
V2=V1/V3
ENDIF
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import division_by_zero
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, division_by_zero,
      messages={"division-by-zero": "'{op} 0': division by zero has no result"})
