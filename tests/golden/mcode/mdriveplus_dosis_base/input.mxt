' Written for mcc after github.com/greezybacon/mcontrol,
' drivers/mdrive/microcode/modules/dosis-1.x/mdrive_base.mxt (no licence found: the constructs,
' not the text). One-letter variables, Lexium names used as user names (LO, BM, DJ, FS, F1, AO,
' AJ, LS, AB), OL and IL for I/O points 1-4 as a bank; the real file reads BC, which it never
' declares: the one true mistake reported here (M117).
CE=2
DG=1
ES=3
EE=1
MS=256
SF=100
HT=500
OL 0
S1=0,0,0
S2=0,0,0
VA X=204
VA R=0
VA T=0
VA PD=0
VA LO=12200
VA BM=750
VA DJ=0
VA FS=0
VA F1=410
VA KF=0
PG 1000
LB AO
 OL 0
 R=LO
 CL ME
 E
LB AJ
 OL 1
 H 1
 OL 0
 KF = IL
 CL AB, KF & 4 = 4
 FS = F1 + DJ
 R=BC
 E
LB ME
 MA R
 H
 T=P
 PD=T-R
 RT
LB AB
 PD=PD*-1
 RT
LB LS
 BM=X
 E
PG
