vs_1_1
def c9, 0.5, 0, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
dp4 r0.x, v0, c0
dp4 r1.x, v0, c1
dp4 r2.x, v0, c2
dp3 r3.x, v1, c0
dp3 r3.y, v1, c1
dp3 r3.z, v1, c2
dp4 oPos.x, v0, c4
dp4 oPos.y, v0, c5
dp4 oPos.z, v0, c6
dp4 oPos.w, v0, c7
dp3 r4.x, r3, r3
rsq r5.x, r4.x
mul r4.xyz, r3, r5.x
mad oT1.xyz, r4, c9.x, c9.x
mov r3.x, -r0
mov r3.y, -r1.x
mov r3.z, -r2.x
add oT2.xyz, c8, r3
mov oT0.xy, v2
