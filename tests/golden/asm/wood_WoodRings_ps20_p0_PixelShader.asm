ps_2_0
def c14, 0, 1.25, -2, 3
def c15, -0.83, 5.88235294, 0.3, 0.7
dcl t0
dcl t1
dcl v0
dcl_volume s0
mul r0.xyz, t0, c0.x
texld r1, r0, s0
mad r2.xyz, r1, c1.x, r0
mul r0.x, r2.z, r2.z
mad r1.x, r2.y, r2.y, r0
rsq r0.x, r1.x
rcp r1.x, r0.x
mul r0.x, r1, c2
mov r1.x, r0
mov r1.yz, c14.x
texld r2, r1, s0
mul r1.x, r2, c1
abs r2.x, r1
add r1.x, r0, r2
frc r0.x, r1
mul r1.x, r0, c14.y
mov_sat r2.x, r1
mul r1.x, r2, r2
mad r3.x, c14.z, r2, c14.w
add r2.x, r0, c15.x
mul r0.x, r2, c15.y
mov_sat r2.x, r0
mul r0.x, r2, r2
mad r4.x, c14.z, r2, c14.w
mul r2.x, r0, r4
mad r0.x, r1, r3, -r2
dp3 r1.x, t1, c6
mul r2.xyz, c5, r1.x
mul r1.xyz, r2, c7.x
mad r2.xyz, c3, c4.x, r1
lrp r1.xyz, r0.x, c9, c8
mul r3.xyz, r2, r1
add r1.xyz, c6, -c10
dp3 r2.x, r1, r1
rsq r4.x, r2.x
mul r2.xyz, r1, r4.x
dp3 r1.x, r2, t1
rcp r2.x, c11.x
pow r4.x, r1.x, r2.x
mul r1.xyz, c12, r4.x
mad r2.x, c15.z, r0, c15.w
mul r0.x, c13, r2
mul r2.xyz, r1, r0.x
mad r0.xyz, r3, v0.w, r2
mov r0.w, v0
mov oC0, r0
