; Pick and place with a gripper on a 3-axis gantry (X, Y, Z).
; Waits for the part-present sensor (DI1 = 1), moves over the pick point,
; lowers Z, closes the gripper (DO1 = 1), lifts, moves to the drop point,
; lowers, opens the gripper and lifts again. V1 counts the parts placed.
; Stops after 10 parts or when the stop button (DI2 = 1) is pressed, then
; parks the gantry at 0,0 and lights the "cycle done" lamp (DO8).
; Z is 0 at the top; negative targets go down.
ABS
HSPD=30000
LSPD=500
ACC=250
DO=0
; V1 = parts placed, V2 = 1 once the program must stop
V1=0
V2=0
WHILE V2=0
; wait for a part, polling every 10 ms
WHILE DI1=0
DELAY=10
ENDWHILE
; pick
X12000Y4000
WAITX
WAITY
Z-6000
WAITZ
DO1=1
; give the gripper time to close
DELAY=250
Z0
WAITZ
; place
X30000Y18000
WAITX
WAITY
Z-4000
WAITZ
DO1=0
DELAY=200
Z0
WAITZ
V1=V1+1
; a host can read the count from V1
IF V1>=10
V2=1
ENDIF
IF DI2=1
V2=1
ENDIF
ENDWHILE
; park and signal the end of the cycle
X0Y0
WAITX
WAITY
DO8=1
END
