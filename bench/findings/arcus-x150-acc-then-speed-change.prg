; bench/fuzz_codegen.py finding (arcus seed 6, minimized): KNOWN (issue 23, "the X150 writer keeps an A
; after a speed change without converting it again").
; mcc compile --target x150: S010 - ACC=300 is a ramp TIME; X150 A is a rate computed from the speeds
; where ACC is set (HSPD=8000) and not again after HSPD=4000, so the move ramps in 150 ms, not 300.
HSPD=8000
LSPD=100
ACC=300
HSPD=4000
INC
X3000
WAITX
END
