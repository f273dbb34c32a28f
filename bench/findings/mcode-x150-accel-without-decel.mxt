' bench/fuzz_codegen.py finding (mcode seed 72, minimized): KNOWN (issue 23, "MCode defaults").
' mcc compile --target x150: S010 - only A is set; the source decelerates at MCode's default D, the
' X150 output at A (X150 has one ramp), so the move ends 25 ms early. The backend should refuse (or
' write the default D's ramp) when the deceleration in force is the device default.
PG 100
LB M1
A=1000000
MA -51200
H
E
PG
