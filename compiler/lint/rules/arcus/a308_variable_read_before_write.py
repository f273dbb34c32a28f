r"""# A308 variable-read-before-write

A variable is read on a path where the program has not written it yet.

- kind: lint
- default severity: warning
- dialects: arcus
- fix available: no
- manual: L833-L844, L2669-L2698

## What it means

The 64 variables V0-V63 (L2671) are not stored in flash (L833-L844): after a power cycle their
value is whatever the firmware starts with, which the manual does not state. Reading one before
the program sets it makes the program depend on that, or on a host having set it. Initialise it
first (`V1=0`). A subroutine is checked with what holds at every `GOSUB` of it.

## Bad

```
V2=V1+1
END
```

## Good

```
V1=0
V2=V1+1
END
```
"""

from __future__ import annotations

from mcc.compiler.lint.rules.shared import variable_read_before_write
from mcc.compiler.lint.rules.shared.voice import speak


speak(__name__, variable_read_before_write,
      messages={"variable-read-before-write": "{name} is read before the program writes it on some path: variables "
                                              "are not kept in flash; set it first (e.g. {name}=0)"})
