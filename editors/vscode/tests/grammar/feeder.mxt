' SYNTAX TEST "source.mcode" "labels, variables, commands, comments"
VA Np=0   ` parts placed
' <- storage.type.mcode
'  ^^ variable.other.mcode
'    ^ keyword.operator.mcode
'     ^ constant.numeric.mcode
'         ^^^^^^^^^^^^^^ comment.line.mcode
LB G1
' <- keyword.control.mcode
'  ^^ entity.name.label.mcode
  BR G1,I1=0
' ^^ keyword.control.mcode
'    ^^ variable.other.label.mcode
  MA 51200
' ^^ support.function.mcode
'    ^^^^^ constant.numeric.mcode
  PR "Parts: ",Np
'    ^^^^^^^^^ string.quoted.double.mcode
