// phong.fx technique SingleTexture, lowered for g400
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program 39d380c8a22522ed
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
uniform vec4 u_light0_position;
uniform vec4 u_light0_attenuation;
uniform vec4 u_light0_ambient;
uniform vec4 u_normal_c0;
uniform vec4 u_normal_c1;
uniform vec4 u_normal_c2;
uniform vec4 u_light0_diffuse;
uniform vec4 u_material_power;
uniform vec4 u_light0_specular;
uniform vec4 u_material_ambient;
uniform vec4 u_material_emissive;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_color1;
out vec4 vary_texcoord0;

void main() {
#line 27
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
    vec4 v26 = u_light0_position;  // %26 = input light0_position
    vec4 v27 = u_light0_attenuation;  // %27 = input light0_attenuation
    vec4 v28 = (v26 - v11);  // %28 = sub %26, %11
    vec4 v29 = vec4(v28.x, v28.y, v28.z, v24.w);  // %29 = merge %28, %24 mask=w
    vec4 v30 = vec4(dot(v29.xyz, v29.xyz));  // %30 = dp3 %29, %29
    vec4 v31 = mix(inversesqrt(abs(v30)), vec4(uintBitsToFloat(0x7F800000u)), equal(v30, vec4(0.0)));  // %31 = rsq %30
    vec4 v32 = (v30 * v31);  // %32 = mul %30, %31
    vec4 v33 = (v29 * v31);  // %33 = mul %29, %31
    vec4 v34 = vec4(v25.x, v32.y, v25.z, v25.w);  // %34 = merge %25, %32 mask=y
    vec4 v35 = vec4(v34.x, v34.y, v30.z, v34.w);  // %35 = merge %34, %30 mask=z
    vec4 v36 = vec4(dot(v35.xyz, v27.xyz));  // %36 = dp3 %35, %27
    vec4 v37 = mix(1.0 / v36, vec4(uintBitsToFloat(0x7F800000u)), equal(v36, vec4(0.0)));  // %37 = rcp %36
    vec4 v38 = v27.wwww;  // %38 = swizzle %27 pattern=wwww
    vec4 v39 = (v38 - v32);  // %39 = sub %38, %32
    vec4 v40 = mix(v24, v37, greaterThanEqual(v39, vec4(0.0)));  // %40 = cmp %39, %37, %24
    vec4 v41 = u_light0_ambient;  // %41 = input light0_ambient
    vec4 v42 = (v41 * v40);  // %42 = mul %41, %40
    vec4 v43 = attr_normal;  // %43 = input normal
    vec4 v44 = u_normal_c0;  // %44 = input normal_c0
    vec4 v45 = u_normal_c1;  // %45 = input normal_c1
    vec4 v46 = u_normal_c2;  // %46 = input normal_c2
    vec4 v47 = vec4(dot(v43.xyz, v44.xyz));  // %47 = dp3 %43, %44
    vec4 v48 = vec4(dot(v43.xyz, v45.xyz));  // %48 = dp3 %43, %45
    vec4 v49 = vec4(dot(v43.xyz, v46.xyz));  // %49 = dp3 %43, %46
    vec4 v50 = vec4(v47.x, v48.y, v47.z, v47.w);  // %50 = merge %47, %48 mask=y
    vec4 v51 = vec4(v50.x, v50.y, v49.z, v50.w);  // %51 = merge %50, %49 mask=z
    vec4 v52 = vec4(v51.x, v51.y, v51.z, v25.w);  // %52 = merge %51, %25 mask=w
    vec4 v53 = vec4(v52.x, v52.y, v52.z, v24.w);  // %53 = merge %52, %24 mask=w
    vec4 v54 = (v53 * (dot(v53.xyz, v53.xyz) != 0.0 ? inversesqrt(dot(v53.xyz, v53.xyz)) : 3.4028235e+38));  // %54 = nrm %53
    vec4 v55 = vec4(dot(v54.xyz, v33.xyz));  // %55 = dp3 %54, %33
    vec4 v56 = clamp(v55, 0.0, 1.0);  // %56 = saturate %55
    vec4 v57 = u_light0_diffuse;  // %57 = input light0_diffuse
    vec4 v58 = (v56 * v57);  // %58 = mul %56, %57
    vec4 v59 = (v58 * v40);  // %59 = mul %58, %40
    vec4 v60 = vec4(v59.x, v59.y, v59.z, v24.w);  // %60 = merge %59, %24 mask=w
    vec4 v61 = (-v11);  // %61 = neg %11
    vec4 v62 = vec4(v61.x, v61.y, v61.z, v24.w);  // %62 = merge %61, %24 mask=w
    vec4 v63 = (v62 * (dot(v62.xyz, v62.xyz) != 0.0 ? inversesqrt(dot(v62.xyz, v62.xyz)) : 3.4028235e+38));  // %63 = nrm %62
    vec4 v64 = (v33 + v63);  // %64 = add %33, %63
    vec4 v65 = vec4(v64.x, v64.y, v64.z, v24.w);  // %65 = merge %64, %24 mask=w
    vec4 v66 = (v65 * (dot(v65.xyz, v65.xyz) != 0.0 ? inversesqrt(dot(v65.xyz, v65.xyz)) : 3.4028235e+38));  // %66 = nrm %65
    vec4 v67 = vec4(dot(v54.xyz, v66.xyz));  // %67 = dp3 %54, %66
    vec4 v68 = u_material_power;  // %68 = input material_power
    vec4 v69 = v68.xxxx;  // %69 = swizzle %68 pattern=xxxx
    vec4 v70 = vec4(lessThan(v24, v55));  // %70 = slt %24, %55
    vec4 v71 = vec4(lessThan(v24, v67));  // %71 = slt %24, %67
    vec4 v72 = (v70 * v71);  // %72 = mul %70, %71
    vec4 v73 = mix(pow(abs(v67), v69), mix(vec4(uintBitsToFloat(0x7F800000u)), vec4(1.0), equal(v69, vec4(0.0))), bvec4(vec4(lessThanEqual(v69, vec4(0.0))) * vec4(equal(v67, vec4(0.0)))));  // %73 = pow %67, %69
    vec4 v74 = (v73 * v72);  // %74 = mul %73, %72
    vec4 v75 = u_light0_specular;  // %75 = input light0_specular
    vec4 v76 = (v74 * v75);  // %76 = mul %74, %75
    vec4 v77 = (v76 * v40);  // %77 = mul %76, %40
    vec4 v78 = (v23 + v42);  // %78 = add %23, %42
    vec4 v79 = attr_color0;  // %79 = input color0
    vec4 v80 = u_material_ambient;  // %80 = input material_ambient
    vec4 v81 = u_material_emissive;  // %81 = input material_emissive
    vec4 v82 = (v79 * v60 + v81);  // %82 = mad %79, %60, %81
    vec4 v83 = (v80 * v78 + v82);  // %83 = mad %80, %78, %82
    vec4 v84 = vec4(v83.x, v83.y, v83.z, v79.w);  // %84 = merge %83, %79 mask=w
    vec4 v85 = attr_color1;  // %85 = input color1
    vec4 v86 = (v85 * v77);  // %86 = mul %85, %77
    vec4 v87 = clamp(v84, 0.0, 1.0);  // %87 = saturate %84
    vec4 v88 = clamp(v86, 0.0, 1.0);  // %88 = saturate %86
    vec4 v89 = attr_texcoord0;  // %89 = input texcoord0
    vec4 out_position = v22;  // output position = %22
    vec4 out_color0 = v87;  // output color0 = %87
    vec4 out_color1 = v88;  // output color1 = %88
    vec4 out_texcoord0 = v89;  // output texcoord0 = %89
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_color1 = clamp(out_color1, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
