vs_1_1
def c15, 1, 0, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
dp4 r0.x, v0, c0
dp4 r1.x, v0, c1
dp4 r2.x, v0, c2
dp3 r3.x, v1, c0
dp3 r3.y, v1, c1
dp3 r3.z, v1, c2
dp3 r4.x, r3, r3
rsq r5.x, r4.x
mul r4.xyz, r3, r5.x
mov r3.x, -r0
mov r3.y, -r1.x
mov r3.z, -r2.x
add r5.xyz, c4, r3
dp3 r3.x, r5, r5
rsq r6.x, r3.x
mul r3.xyz, r5, r6.x
mov r5.x, r0
mov r5.y, r1.x
mov r5.z, r2.x
mov r5.w, c15.x
dp4 oPos.x, r5, c5
dp4 oPos.y, r5, c6
dp4 oPos.z, r5, c7
dp4 oPos.w, r5, c8
dp3 r0.x, r4, -c9
max r1.x, r0, c15.y
min r0.x, r1, c15.x
mul r1, r0.x, c10
mul oD0.xyz, r1, c11
mul oT0.xyz, v0, c14.x
dp3 r0.x, r4, -r3
add r1.x, r0, r0
mad oT1.xyz, -r1.x, r4, -r3
mov oD0.w, c15.x
mov oT2.xy, v2
