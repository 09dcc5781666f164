vs_1_1
def c15, 1, 0, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
dp4 r0.x, v0, c0
dp4 r0.y, v0, c1
dp4 r0.z, v0, c2
dp3 r1.x, v1, c0
dp3 r1.y, v1, c1
dp3 r1.z, v1, c2
dp3 r2.x, r1, r1
rsq r2.x, r2.x
mul r1.xyz, r1, r2.x
add r2.xyz, c4, -r0
dp3 r3.x, r2, r2
rsq r3.x, r3.x
mul r2.xyz, r2, r3.x
mov r0.w, c15.x
dp4 oPos.x, r0, c5
dp4 oPos.y, r0, c6
dp4 oPos.z, r0, c7
dp4 oPos.w, r0, c8
dp3 r0.x, r1, -c9
max r0.x, r0, c15.y
min r0.x, r0, c15.x
mul r0.xyz, r0.x, c10
mul oD0.xyz, r0, c11
mul oT0.xyz, v0, c14.x
dp3 r0.x, r1, -r2
add r0.x, r0, r0
mad oT1.xyz, -r0.x, r1, -r2
mov oD0.w, c15.x
mov oT2.xy, v2
