vs_1_1
def c8, 0.5, 0, 0, 0
dcl_position v0
dcl_normal v1
dcl_texcoord v2
dp4 r0.x, v0, c4
dp4 r0.y, v0, c5
dp4 r0.z, v0, c6
dp3 r1.x, v1, c4
dp3 r1.y, v1, c5
dp3 r1.z, v1, c6
dp4 oPos.x, v0, c0
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
dp3 r2.x, r1, r1
rsq r2.x, r2.x
mul r1.xyz, r1, r2.x
mad oT1.xyz, r1, c8.x, c8.x
add oT2.xyz, c7, -r0
mov oT0.xy, v2
