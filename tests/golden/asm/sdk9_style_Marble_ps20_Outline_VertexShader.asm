vs_1_1
def c12, 0.0399999991, 1, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
mov r0.xyz, v0
mad r0.xyz, v1, c12.x, r0
mov r0.w, v0
dp4 r1.x, r0, c4
dp4 r1.y, r0, c5
dp4 r1.z, r0, c6
dp3 r0.x, v1, c4
dp3 r0.y, v1, c5
dp3 r0.z, v1, c6
dp3 r2.x, r0, r0
rsq r2.x, r2.x
mul r0.xyz, r0, r2.x
add r2.xyz, c7, -r1
dp3 r3.x, r2, r2
rsq r3.x, r3.x
mul r2.xyz, r2, r3.x
mov r1.w, c12.y
dp4 oPos.x, r1, c0
dp4 oPos.y, r1, c1
dp4 oPos.z, r1, c2
dp4 oPos.w, r1, c3
dp3 r1.x, r0, -c8
max r1.x, r1, c12.z
min r1.x, r1, c12.y
mul r1.xyz, r1.x, c9
mul oD0.xyz, r1, c11
mul oT0.xyz, v0, c10.x
dp3 r1.x, r0, -r2
add r1.x, r1, r1
mad oT1.xyz, -r1.x, r0, -r2
mov oD0.w, c12.y
mov oT2.xy, v2
