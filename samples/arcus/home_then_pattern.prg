; Homing, then a serpentine pattern on an X/Y table.
; 1. Enables the X and Y drivers (EO1, EO2) and homes X and Y on their
;    home switches (HOME = homing mode 0) at a slow speed, one axis at a time.
; 2. Zeroes the pulse and encoder counters (homing leaves the axis slightly
;    past the switch because of the ramp-down).
; 3. Traces three passes of a serpentine 20000 x 10000 pulses at working speed,
;    then returns to 0,0 with a linear interpolated move and disables the drivers.
; Moves are absolute; every move is followed by WAIT on its axes.
ABS
; --- slow homing speeds: pulses/s, ACC is the ramp time in ms
HSPD=5000
LSPD=500
ACC=200
; enable the X and Y drivers (EO1, EO2)
EO=3
HOMEX-
WAITX
HOMEY-
WAITY
; --- zero the counters
PX=0
PY=0
EX=0
EY=0
; --- working speeds
HSPD=40000
LSPD=1000
ACC=300
; --- pass 1: left to right
X20000
WAITX
Y5000
WAITY
; --- pass 2: right to left
X0
WAITX
Y10000
WAITY
; --- pass 3: left to right
X20000
WAITX
; --- back to the origin diagonally (linear interpolation of X and Y)
X0Y0
WAITX
WAITY
EO=0
END
