// hemisphere.fx technique SingleTexture, lowered for g400
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program c4d21751ff7a667b
in vec4 attr_position;
in vec4 attr_normal;
in vec4 attr_color0;
in vec4 attr_color1;
in vec4 attr_texcoord0;
uniform vec4 u_world_view_c0;
uniform vec4 u_world_view_c1;
uniform vec4 u_world_view_c2;
uniform vec4 u_world_view_c3;
uniform vec4 u_projection_c0;
uniform vec4 u_projection_c1;
uniform vec4 u_projection_c2;
uniform vec4 u_projection_c3;
uniform vec4 u_ambient;
uniform vec4 u_light0_direction;
uniform vec4 u_light0_ambient;
uniform vec4 u_normal_c0;
uniform vec4 u_normal_c1;
uniform vec4 u_normal_c2;
uniform vec4 u_light0_diffuse;
uniform vec4 u_material_ambient;
uniform vec4 u_material_emissive;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;

void main() {
#line 24
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_world_view_c0;  // %1 = input world_view_c0
    vec4 v2 = u_world_view_c1;  // %2 = input world_view_c1
    vec4 v3 = u_world_view_c2;  // %3 = input world_view_c2
    vec4 v4 = u_world_view_c3;  // %4 = input world_view_c3
    vec4 v5 = vec4(dot(v0, v1));  // %5 = dp4 %0, %1
    vec4 v6 = vec4(dot(v0, v2));  // %6 = dp4 %0, %2
    vec4 v7 = vec4(dot(v0, v3));  // %7 = dp4 %0, %3
    vec4 v8 = vec4(dot(v0, v4));  // %8 = dp4 %0, %4
    vec4 v9 = vec4(v5.x, v6.y, v5.z, v5.w);  // %9 = merge %5, %6 mask=y
    vec4 v10 = vec4(v9.x, v9.y, v7.z, v9.w);  // %10 = merge %9, %7 mask=z
    vec4 v11 = vec4(v10.x, v10.y, v10.z, v8.w);  // %11 = merge %10, %8 mask=w
    vec4 v12 = u_projection_c0;  // %12 = input projection_c0
    vec4 v13 = u_projection_c1;  // %13 = input projection_c1
    vec4 v14 = u_projection_c2;  // %14 = input projection_c2
    vec4 v15 = u_projection_c3;  // %15 = input projection_c3
    vec4 v16 = vec4(dot(v11, v12));  // %16 = dp4 %11, %12
    vec4 v17 = vec4(dot(v11, v13));  // %17 = dp4 %11, %13
    vec4 v18 = vec4(dot(v11, v14));  // %18 = dp4 %11, %14
    vec4 v19 = vec4(dot(v11, v15));  // %19 = dp4 %11, %15
    vec4 v20 = vec4(v16.x, v17.y, v16.z, v16.w);  // %20 = merge %16, %17 mask=y
    vec4 v21 = vec4(v20.x, v20.y, v18.z, v20.w);  // %21 = merge %20, %18 mask=z
    vec4 v22 = vec4(v21.x, v21.y, v21.z, v19.w);  // %22 = merge %21, %19 mask=w
    vec4 v23 = u_ambient;  // %23 = input ambient
    vec4 v24 = vec4(0.0, 0.0, 0.0, 0.0);  // %24 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v25 = vec4(1.0, 1.0, 1.0, 1.0);  // %25 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v26 = u_light0_direction;  // %26 = input light0_direction
    vec4 v27 = u_light0_ambient;  // %27 = input light0_ambient
    vec4 v28 = (v27 * v25);  // %28 = mul %27, %25
    vec4 v29 = attr_normal;  // %29 = input normal
    vec4 v30 = u_normal_c0;  // %30 = input normal_c0
    vec4 v31 = u_normal_c1;  // %31 = input normal_c1
    vec4 v32 = u_normal_c2;  // %32 = input normal_c2
    vec4 v33 = vec4(dot(v29.xyz, v30.xyz));  // %33 = dp3 %29, %30
    vec4 v34 = vec4(dot(v29.xyz, v31.xyz));  // %34 = dp3 %29, %31
    vec4 v35 = vec4(dot(v29.xyz, v32.xyz));  // %35 = dp3 %29, %32
    vec4 v36 = vec4(v33.x, v34.y, v33.z, v33.w);  // %36 = merge %33, %34 mask=y
    vec4 v37 = vec4(v36.x, v36.y, v35.z, v36.w);  // %37 = merge %36, %35 mask=z
    vec4 v38 = vec4(v37.x, v37.y, v37.z, v25.w);  // %38 = merge %37, %25 mask=w
    vec4 v39 = vec4(v38.x, v38.y, v38.z, v24.w);  // %39 = merge %38, %24 mask=w
    vec4 v40 = vec4(dot(v39.xyz, v26.xyz));  // %40 = dp3 %39, %26
    vec4 v41 = clamp(v40, 0.0, 1.0);  // %41 = saturate %40
    vec4 v42 = u_light0_diffuse;  // %42 = input light0_diffuse
    vec4 v43 = (v41 * v42);  // %43 = mul %41, %42
    vec4 v44 = (v43 * v25);  // %44 = mul %43, %25
    vec4 v45 = vec4(v44.x, v44.y, v44.z, v24.w);  // %45 = merge %44, %24 mask=w
    vec4 v46 = (v23 + v28);  // %46 = add %23, %28
    vec4 v47 = attr_color0;  // %47 = input color0
    vec4 v48 = u_material_ambient;  // %48 = input material_ambient
    vec4 v49 = u_material_emissive;  // %49 = input material_emissive
    vec4 v50 = (v47 * v45 + v49);  // %50 = mad %47, %45, %49
    vec4 v51 = (v48 * v46 + v50);  // %51 = mad %48, %46, %50
    vec4 v52 = vec4(v51.x, v51.y, v51.z, v47.w);  // %52 = merge %51, %47 mask=w
    vec4 v53 = attr_color1;  // %53 = input color1
    vec4 v54 = clamp(v52, 0.0, 1.0);  // %54 = saturate %52
    vec4 v55 = clamp(v53, 0.0, 1.0);  // %55 = saturate %53
    vec4 v56 = attr_texcoord0;  // %56 = input texcoord0
    vec4 out_position = v22;  // output position = %22
    vec4 out_color0 = v54;  // output color0 = %54
    vec4 out_color1 = v55;  // output color1 = %55
    vec4 out_texcoord0 = v56;  // output texcoord0 = %56
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
