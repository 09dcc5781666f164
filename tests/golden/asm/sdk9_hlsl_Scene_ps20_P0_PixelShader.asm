ps_2_0
def c4, 0.5, 1, 0, 0
dcl t0
dcl t1
dcl t2
dcl_2d s0
nrm r0.xyz, t1
dp3 r1.x, r0, c0
mov_sat r2.x, r1
texld r1, t0, s0
mad r3, c2, r2.x, c1
nrm r2.xyz, t2
add r4.xyz, c0, r2
nrm r2.xyz, r4
dp3 r4.x, r0, r2
mov_sat r0.x, r4
pow r2.x, r0.x, c3.x
mul r0.x, r2, c4.x
mad r2.xyz, r1, r3, r0.x
mov r2.w, c4.y
mov oC0, r2
