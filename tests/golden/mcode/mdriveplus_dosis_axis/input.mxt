' Written for mcc after github.com/greezybacon/mcontrol,
' drivers/mdrive/microcode/modules/dosis-1.x/xAxis.mxt (no licence found: the constructs, not the
' text). Values written without `=` (EE 1, A 8192, S1 1,0,0, P 0, R1 0), an encoder axis retrying
' a move while it stalls, and PR items with a comma missing, which the drive reads as a mistake
' (M123 with its fix). The real file compares PD <=DB; reading DB in a condition is a
' compile limitation of mcc for every MCode profile (S010), so 50 stands for it here.
VA Q1 = 0
VA PD = 0
EE 1
ES 3
A 8192
D 16384
DB 50
VM 4096
VI 400
RC 100
HC 50
SF 600
S1 1,0,0
S2 16,0,0
PG 100
LB M1
 ST 0
 ER 0
 HM 3
 H
 P 0
 BR G9, ST<>0
 BR G8
LB G1
 R1 0
 PD 0
LB G2
 BR G9, R1>3
 ST 0
 MA Q1
 H
 PD = Q1 - P
 CL ZC, PD < 0
 BR G8, PD <= 50
 IC R1
 H 100
 BR G2, ST<>0
 BR G8
LB G3
 PR "Position ", P, " Stall " ST
 E
LB G8
 PR "1"
 E
LB G9
 PR "0"
 E
LB ZC
 PD = PD * -1
 RT
PG
CK=0
EM=1
S
' end
