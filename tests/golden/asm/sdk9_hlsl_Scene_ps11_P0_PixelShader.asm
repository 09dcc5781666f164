ps_1_1
def c3, 0, 0, 0, 1
tex t0
texcoord t1
dp3_sat r0, t1_bx2, c0
mad r0, c1, r0, c2
mul r0.rgb, t0, r0
+mov r0.a, c3
