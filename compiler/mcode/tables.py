"""Drive data the MCode lowering and the virtual device both read: the setups a drive keeps per
line, which PR reports as a table, and the version it reports without a profile's.

IS (inputs), OS (outputs) and LS (software limits) are set one line at a time
(`OS=<line>,<type>,<active>`) and `PR OS` answers every line's setup. Both the lowering (which
turns `PR OS` into one neutral print per line) and the virtual device (link/device/mcode.py) read
this table, so `mcc sim` and `mcc device` answer the same.

name -> ({line: the factory value of its other parameters}, how PR writes one line):
IS: inputs 1-4 type 0 LOW active (L3504-L3506), the analog input 5 voltage 0-5 V (L3557-L3561),
the index input 6 LOW active (L3595-L3600); OS: outputs 1-3 type 16 LOW active (L4618-L4621, the
reply of L4647-L4650); LS: the minus (0) and plus (1) limits at 0, disabled (L4023-L4026, the
reply format of L4044).
"""

from __future__ import annotations

# What `PR VR` answers when the product profile gives no `[device] version`: mcc's own stand-in
# (docs/PROFILES.md), the same for `mcc sim` and the virtual device.
STAND_IN_VERSION = "LMDCM 6.002"

TABLES: dict[str, tuple[dict[int, tuple[int, ...]], str]] = {
    "IS": ({1: (0, 0), 2: (0, 0), 3: (0, 0), 4: (0, 0), 5: (9, 0), 6: (0, 0)}, "IS = {n}, {0}, {1}"),
    "OS": ({1: (16, 0), 2: (16, 0), 3: (16, 0)}, "OS = {n}, {0}, {1}"),
    "LS": ({0: (0, 0), 1: (0, 0)}, "LS={n}, {0}, {1}"),
}
