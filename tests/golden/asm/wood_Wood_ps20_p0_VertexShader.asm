vs_1_1
dcl_position v0
dcl_normal v1
dcl_color v2
dp4 oPos.x, v0, c0
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
dp3 r0.x, v1, v1
rsq r0.x, r0.x
mul oT1.xyz, v1, r0.x
mov oD0, v2
mov oT0.xyz, v0
