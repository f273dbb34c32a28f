; bench/fuzz_codegen.py finding (feature initial_speed): NEW.
; mcc compile --target x150: X205 then S010 - X150 has no initial speed, so the backend drops LSPD and
; keeps A = (HSPD - LSPD) / ACC: the move ramps from 0 and ends 58 ms late (0.883 s, source 0.825 s).
; Either A must be HSPD / ACC (the ramp time kept) or the output refused when LSPD is not negligible.
; With LSPD=100 the error is about 1 % per move and adds up in loops (arcus seed 21 of the bounded test).
HSPD=4000
LSPD=1000
ACC=100
INC
X3000
WAITX
END
