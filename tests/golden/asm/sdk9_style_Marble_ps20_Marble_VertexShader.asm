vs_1_1
def c12, 1, 0, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
dp4 r0.x, v0, c4
dp4 r0.y, v0, c5
dp4 r0.z, v0, c6
dp3 r1.x, v1, c4
dp3 r1.y, v1, c5
dp3 r1.z, v1, c6
dp3 r2.x, r1, r1
rsq r2.x, r2.x
mul r1.xyz, r1, r2.x
add r2.xyz, c7, -r0
dp3 r3.x, r2, r2
rsq r3.x, r3.x
mul r2.xyz, r2, r3.x
mov r0.w, c12.x
dp4 oPos.x, r0, c0
dp4 oPos.y, r0, c1
dp4 oPos.z, r0, c2
dp4 oPos.w, r0, c3
dp3 r0.x, r1, -c8
max r0.x, r0, c12.y
min r0.x, r0, c12.x
mul r0.xyz, r0.x, c9
mul oD0.xyz, r0, c11
mul oT0.xyz, v0, c10.x
dp3 r0.x, r1, -r2
add r0.x, r0, r0
mad oT1.xyz, -r0.x, r1, -r2
mov oD0.w, c12.x
mov oT2.xy, v2
