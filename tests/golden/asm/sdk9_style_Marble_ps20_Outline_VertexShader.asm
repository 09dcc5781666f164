vs_1_1
def c15, 0.0399999991, 1, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
mov r0, v0
mad r1.xyz, v1, c15.x, r0
mov r1.w, v0
dp4 r0.x, r1, c0
dp4 r2.x, r1, c1
dp4 r3.x, r1, c2
dp3 r1.x, v1, c0
dp3 r1.y, v1, c1
dp3 r1.z, v1, c2
dp3 r4.x, r1, r1
rsq r5.x, r4.x
mul r4.xyz, r1, r5.x
mov r1.x, -r0
mov r1.y, -r2.x
mov r1.z, -r3.x
add r5.xyz, c4, r1
dp3 r1.x, r5, r5
rsq r6.x, r1.x
mul r1.xyz, r5, r6.x
mov r5.x, r0
mov r5.y, r2.x
mov r5.z, r3.x
mov r5.w, c15.y
dp4 oPos.x, r5, c5
dp4 oPos.y, r5, c6
dp4 oPos.z, r5, c7
dp4 oPos.w, r5, c8
dp3 r0.x, r4, -c9
max r2.x, r0, c15.z
min r0.x, r2, c15.y
mul r2, r0.x, c10
mul oD0.xyz, r2, c11
mul oT0.xyz, v0, c14.x
dp3 r0.x, r4, -r1
add r2.x, r0, r0
mad oT1.xyz, -r2.x, r4, -r1
mov oD0.w, c15.y
mov oT2.xy, v2
