ps_2_0
def c14, 0, 3, 2, 1
def c15, -2, 0.8, 0.83, 0.3
def c16, 0.7, 0, 0, 0
dcl t0.xyz
dcl t1.xyz
dcl v0
dcl_volume s0
mul r0.xyz, t0, c1.x
texld r1, r0, s0
mad r0.yz, r1, c2.x, r0
mul r1.x, r0.z, r0.z
mad r0.x, r0.y, r0.y, r1
rsq r0.x, r0.x
rcp r0.x, r0.x
mul r0.x, r0, c0
mov r1.x, r0
mov r1.yz, c14.x
texld r1, r1, s0
mul r1.x, r1, c2
abs r1.x, r1
add r0.x, r0, r1
frc r1.x, r0
mul r0.x, r1, r1
mul r2.x, r1, r0
mul r3.x, c14.y, r0
mad r4.x, c14.z, r2, -r3
add r4.x, r4, c14.w
mad r5.x, c15.x, r0, r2
add r5.x, r5, r1
mad r3.x, c15.x, r2, r3
add r0.x, r2, -r0
add r2.x, c14.w, -r1
mad r6.x, r3, c15.y, r5
add r6.x, r6, r0
cmp r6.x, r2, r6, c15.y
cmp r6.x, r1, r6, c14.x
mad r4.x, r4, c15.z, r5
add r3.x, r4, r3
add r0.x, r3, r0
cmp r0.x, r2, r0, c14.w
cmp r0.x, r1, r0, c15.z
add r0.x, r6, -r0
dp3 r1.x, t1, c12
mul r1.xyz, c10, r1.x
mul r1.xyz, r1, c6.x
mad r1.xyz, c9, c5.x, r1
lrp r2.xyz, r0.x, c4, c3
mul r1.xyz, r1, r2
add r2.xyz, c12, -c13
dp3 r3.x, r2, r2
rsq r3.x, r3.x
mul r2.xyz, r2, r3.x
dp3 r2.x, r2, t1
rcp r3.x, c8.x
pow r4.x, r2.x, r3.x
mul r2.xyz, c11, r4.x
mad r0.x, c15.w, r0, c16.x
mul r0.x, c7, r0
mul r0.xyz, r2, r0.x
mad r0.xyz, r1, v0.w, r0
mov r0.w, v0
mov oC0, r0
