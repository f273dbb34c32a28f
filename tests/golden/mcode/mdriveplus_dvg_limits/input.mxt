' Written for mcc after github.com/Dennis-van-Gils/python-dvg-devices,
' src/dvg_devices/MDrive_example_motion_program_x.mxt (MIT): its constructs, not its text.
' S1-S4 set up from user variables, labels F1/F2 that a host starts with EX,
' names compared case-insensitively (CL MM / LB Mm), LM limit stop mode.
Dn = "x"
Em = 0
Vi = 25600
Vm = 256000
Rc = 25
VA L1 = 3
VA L2 = 2
S1 = L1, 1, 0
S2 = L2, 1, 0
S3 = 0, 1, 0
Lm = 4
PG 100
LB SU
  P = 0
  CL MM
LB M0
  BR M0
LB Mm
  S1 = L1, 1, 0
  S2 = L2, 1, 0
  RT
LB F1
  SL 0
  H
  BR M0
LB F2
  SL 0
  H
  BR Fh, L1 = 0
  S1 = 1, 1, 0
  HM 1
  H
  R1 = P & 1023
  R2 = 1024 - R1
  MR R2
  H
  P = 0
  CL Mm
  BR M0
LB FH
  RT
PG
