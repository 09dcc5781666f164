ps_2_0
def c4, 0.5, 1, 0, 0
dcl t0.xy
dcl t1.xyz
dcl t2.xyz
dcl_2d s0
nrm r0.xyz, t1
dp3_sat r1.x, r0, c0
texld r2, t0, s0
mad r1.xyz, c1, r1.x, c2
nrm r3.xyz, t2
add r3.xyz, c0, r3
nrm r4.xyz, r3
dp3_sat r0.x, r0, r4
pow r3.x, r0.x, c3.x
mul r0.x, r3, c4.x
mad r0.xyz, r2, r1, r0.x
mov r0.w, c4.y
mov oC0, r0
