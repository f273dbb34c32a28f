` mcc: profile=lmd-c
` an MDrivePlus file read as Lexium: parses, and each family command names the Lexium equivalent
S1 = 3, 1, 0
S2=17,0,0
IS=1,3,1
