; Homing: X runs to its home switch in the minus direction, then indexes to 4000.
ABS
HSPD=4000
LSPD=400
ACC=200
EO=1
HOMEX-
WAITX
X4000
WAITX
DO1=1
END
