` three bad lines: each gets one diagnostic, and the rest is still checked
MA (100)
VM=500000
PR "no closing quote
VI=#
MX 100
H
