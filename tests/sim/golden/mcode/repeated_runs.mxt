' A pattern repeated three times and its first step once more (a machine-made program): -Os
' outlines the repeated run; the runs "O1=1 .. H 20 O1=1" overlap by one line, and only runs
' that do not overlap may be outlined (each place must run its own copy).
PG 100
LB MN
  O1=1
  H 10
  O1=0
  H 20
  O1=1
  H 10
  O1=0
  H 20
  O1=1
  H 10
  O1=0
  H 20
  O1=1
  E
PG
