vs_1_1
def c15, 0.0399999991, 1, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
mov r0.xyz, v0
mad r0.xyz, v1, c15.x, r0
mov r0.w, v0
dp4 r1.x, r0, c0
dp4 r1.y, r0, c1
dp4 r1.z, r0, c2
dp3 r0.x, v1, c0
dp3 r0.y, v1, c1
dp3 r0.z, v1, c2
dp3 r2.x, r0, r0
rsq r2.x, r2.x
mul r0.xyz, r0, r2.x
add r2.xyz, c4, -r1
dp3 r3.x, r2, r2
rsq r3.x, r3.x
mul r2.xyz, r2, r3.x
mov r1.w, c15.y
dp4 oPos.x, r1, c5
dp4 oPos.y, r1, c6
dp4 oPos.z, r1, c7
dp4 oPos.w, r1, c8
dp3 r1.x, r0, -c9
max r1.x, r1, c15.z
min r1.x, r1, c15.y
mul r1.xyz, r1.x, c10
mul oD0.xyz, r1, c11
mul oT0.xyz, v0, c14.x
dp3 r1.x, r0, -r2
add r1.x, r1, r1
mad oT1.xyz, -r1.x, r0, -r2
mov oD0.w, c15.y
mov oT2.xy, v2
