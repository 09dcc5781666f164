ps_1_4
def c3, 0, 0, 0, 1
texld r0, t0
texcrd r1.rgb, t1
dp3_sat r1, r1_bx2, c0
mad r1, c1, r1, c2
mul r0.rgb, r0, r1
+mov r0.a, c3
