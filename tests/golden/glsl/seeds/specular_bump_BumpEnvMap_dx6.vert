// specular_bump.fx technique BumpEnvMap_dx6, lowered for g400
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program daffdc78fb29027a
in vec4 attr_position;
in vec4 attr_normal;
in vec4 attr_texcoord1;
uniform vec4 u_vs_c8;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c10;
uniform vec4 u_vs_c11;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c12;
uniform vec4 u_vs_c16;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c14;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;
out vec4 vary_texcoord2;

void main() {
#line 16
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c8;  // %1 = input vs_c8
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c9;  // %3 = input vs_c9
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c10;  // %6 = input vs_c10
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c11;  // %9 = input vs_c11
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = attr_normal;  // %13 = input normal
    vec4 v14 = u_vs_c0;  // %14 = input vs_c0
    vec4 v15 = vec4(dot(v13.xyz, v14.xyz));  // %15 = dp3 %13, %14
    vec4 v16 = u_vs_c1;  // %16 = input vs_c1
    vec4 v17 = vec4(dot(v13.xyz, v16.xyz));  // %17 = dp3 %13, %16
    vec4 v18 = vec4(v15.x, v17.y, v15.z, v15.w);  // %18 = merge %15, %17 mask=y
    vec4 v19 = u_vs_c2;  // %19 = input vs_c2
    vec4 v20 = vec4(dot(v13.xyz, v19.xyz));  // %20 = dp3 %13, %19
    vec4 v21 = vec4(v18.x, v18.y, v20.z, v18.w);  // %21 = merge %18, %20 mask=z
    vec4 v22 = vec4(0.0, 0.0, 0.0, 0.0);  // %22 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v23 = vec4(v21.x, v21.y, v21.z, v22.w);  // %23 = merge %22, %21 mask=xyz
    vec4 v24 = vec4(dot(v23.xyz, v23.xyz));  // %24 = dp3 %23, %23
    vec4 v25 = vec4(v22.x, v22.y, v22.z, v24.w);  // %25 = merge %22, %24 mask=w
    vec4 v26 = v25.wwww;  // %26 = swizzle %25 pattern=wwww
    vec4 v27 = mix(inversesqrt(abs(v26)), vec4(uintBitsToFloat(0x7F800000u)), equal(v26, vec4(0.0)));  // %27 = rsq %26
    vec4 v28 = vec4(v25.x, v25.y, v25.z, v27.w);  // %28 = merge %25, %27 mask=w
    vec4 v29 = v28.wwww;  // %29 = swizzle %28 pattern=wwww
    vec4 v30 = (v23 * v29);  // %30 = mul %23, %29
    vec4 v31 = vec4(v30.x, v30.y, v30.z, v23.w);  // %31 = merge %23, %30 mask=xyz
    vec4 v32 = u_vs_c12;  // %32 = input vs_c12
    vec4 v33 = (-v32);  // %33 = neg %32
    vec4 v34 = vec4(dot(v31.xyz, v33.xyz));  // %34 = dp3 %31, %33
    vec4 v35 = vec4(v34.x, v22.y, v22.z, v22.w);  // %35 = merge %22, %34 mask=x
    vec4 v36 = v35.xxxx;  // %36 = swizzle %35 pattern=xxxx
    vec4 v37 = max(v36, v22);  // %37 = max %36, %22
    vec4 v38 = vec4(v37.x, v35.y, v35.z, v35.w);  // %38 = merge %35, %37 mask=x
    vec4 v39 = u_vs_c16;  // %39 = input vs_c16
    vec4 v40 = v38.xxxx;  // %40 = swizzle %38 pattern=xxxx
    vec4 v41 = (v39 * v40);  // %41 = mul %39, %40
    vec4 v42 = vec4(dot(v0, v14));  // %42 = dp4 %0, %14
    vec4 v43 = vec4(dot(v0, v16));  // %43 = dp4 %0, %16
    vec4 v44 = vec4(v42.x, v43.y, v42.z, v42.w);  // %44 = merge %42, %43 mask=y
    vec4 v45 = vec4(dot(v0, v19));  // %45 = dp4 %0, %19
    vec4 v46 = vec4(v44.x, v44.y, v45.z, v44.w);  // %46 = merge %44, %45 mask=z
    vec4 v47 = u_vs_c3;  // %47 = input vs_c3
    vec4 v48 = vec4(dot(v0, v47));  // %48 = dp4 %0, %47
    vec4 v49 = vec4(v46.x, v46.y, v46.z, v48.w);  // %49 = merge %46, %48 mask=w
    vec4 v50 = u_vs_c14;  // %50 = input vs_c14
    vec4 v51 = (v50 - v49);  // %51 = sub %50, %49
    vec4 v52 = vec4(v51.x, v51.y, v51.z, v22.w);  // %52 = merge %22, %51 mask=xyz
    vec4 v53 = vec4(dot(v52.xyz, v52.xyz));  // %53 = dp3 %52, %52
    vec4 v54 = vec4(v52.x, v52.y, v52.z, v53.w);  // %54 = merge %52, %53 mask=w
    vec4 v55 = v54.wwww;  // %55 = swizzle %54 pattern=wwww
    vec4 v56 = mix(inversesqrt(abs(v55)), vec4(uintBitsToFloat(0x7F800000u)), equal(v55, vec4(0.0)));  // %56 = rsq %55
    vec4 v57 = vec4(v54.x, v54.y, v54.z, v56.w);  // %57 = merge %54, %56 mask=w
    vec4 v58 = v57.wwww;  // %58 = swizzle %57 pattern=wwww
    vec4 v59 = (v57 * v58);  // %59 = mul %57, %58
    vec4 v60 = vec4(v59.x, v59.y, v59.z, v57.w);  // %60 = merge %57, %59 mask=xyz
    vec4 v61 = (v60 - v32);  // %61 = sub %60, %32
    vec4 v62 = vec4(v61.x, v61.y, v61.z, v60.w);  // %62 = merge %60, %61 mask=xyz
    vec4 v63 = vec4(dot(v62.xyz, v62.xyz));  // %63 = dp3 %62, %62
    vec4 v64 = vec4(v62.x, v62.y, v62.z, v63.w);  // %64 = merge %62, %63 mask=w
    vec4 v65 = v64.wwww;  // %65 = swizzle %64 pattern=wwww
    vec4 v66 = mix(inversesqrt(abs(v65)), vec4(uintBitsToFloat(0x7F800000u)), equal(v65, vec4(0.0)));  // %66 = rsq %65
    vec4 v67 = vec4(v64.x, v64.y, v64.z, v66.w);  // %67 = merge %64, %66 mask=w
    vec4 v68 = v67.wwww;  // %68 = swizzle %67 pattern=wwww
    vec4 v69 = (v67 * v68);  // %69 = mul %67, %68
    vec4 v70 = vec4(v69.x, v69.y, v69.z, v67.w);  // %70 = merge %67, %69 mask=xyz
    vec4 v71 = v70.zzzz;  // %71 = swizzle %70 pattern=zzzz
    vec4 v72 = (-v71);  // %72 = neg %71
    vec4 v73 = vec4(v72.x, v22.y, v22.z, v22.w);  // %73 = merge %22, %72 mask=x
    vec4 v74 = vec4(v73.x, v22.y, v73.z, v73.w);  // %74 = merge %73, %22 mask=y
    vec4 v75 = v70.xxxx;  // %75 = swizzle %70 pattern=xxxx
    vec4 v76 = vec4(v74.x, v74.y, v75.z, v74.w);  // %76 = merge %74, %75 mask=z
    vec4 v77 = vec4(dot(v76.xyz, v76.xyz));  // %77 = dp3 %76, %76
    vec4 v78 = vec4(v76.x, v76.y, v76.z, v77.w);  // %78 = merge %76, %77 mask=w
    vec4 v79 = v78.wwww;  // %79 = swizzle %78 pattern=wwww
    vec4 v80 = mix(inversesqrt(abs(v79)), vec4(uintBitsToFloat(0x7F800000u)), equal(v79, vec4(0.0)));  // %80 = rsq %79
    vec4 v81 = vec4(v78.x, v78.y, v78.z, v80.w);  // %81 = merge %78, %80 mask=w
    vec4 v82 = v81.wwww;  // %82 = swizzle %81 pattern=wwww
    vec4 v83 = (v81 * v82);  // %83 = mul %81, %82
    vec4 v84 = vec4(v83.x, v83.y, v83.z, v81.w);  // %84 = merge %81, %83 mask=xyz
    vec4 v85 = v84.yzxx;  // %85 = swizzle %84 pattern=yzxx
    vec4 v86 = v70.zxyy;  // %86 = swizzle %70 pattern=zxyy
    vec4 v87 = (v85 * v86);  // %87 = mul %85, %86
    vec4 v88 = vec4(v87.x, v87.y, v87.z, v22.w);  // %88 = merge %22, %87 mask=xyz
    vec4 v89 = v84.zxyy;  // %89 = swizzle %84 pattern=zxyy
    vec4 v90 = v70.yzxx;  // %90 = swizzle %70 pattern=yzxx
    vec4 v91 = (-v88);  // %91 = neg %88
    vec4 v92 = (v89 * v90 + v91);  // %92 = mad %89, %90, %91
    vec4 v93 = vec4(v92.x, v92.y, v92.z, v88.w);  // %93 = merge %88, %92 mask=xyz
    vec4 v94 = vec4(dot(v31.xyz, v84.xyz));  // %94 = dp3 %31, %84
    vec4 v95 = vec4(v94.x, v22.y, v22.z, v22.w);  // %95 = merge %22, %94 mask=x
    vec4 v96 = vec4(dot(v31.xyz, v93.xyz));  // %96 = dp3 %31, %93
    vec4 v97 = vec4(v95.x, v96.y, v95.z, v95.w);  // %97 = merge %95, %96 mask=y
    vec4 v98 = v97.xyyy;  // %98 = swizzle %97 pattern=xyyy
    vec4 v99 = vec4(0.32, 0.32, 0.32, 0.32);  // %99 = const (0.32, 0.32, 0.32, 0.32)
    vec4 v100 = (v98 * v99);  // %100 = mul %98, %99
    vec4 v101 = vec4(v100.x, v100.y, v97.z, v97.w);  // %101 = merge %97, %100 mask=xy
    vec4 v102 = v101.xyyy;  // %102 = swizzle %101 pattern=xyyy
    vec4 v103 = vec4(0.5, 0.5, 0.5, 0.5);  // %103 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v104 = (v102 + v103);  // %104 = add %102, %103
    vec4 v105 = vec4(v104.x, v104.y, v12.z, v12.w);  // %105 = merge %12, %104 mask=xy
    vec4 v106 = attr_texcoord1;  // %106 = input texcoord1
    vec4 v107 = vec4(v106.x, v106.y, v12.z, v12.w);  // %107 = merge %12, %106 mask=xy
    vec4 v108 = clamp(v41, 0.0, 1.0);  // %108 = saturate %41
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v108;  // output color0 = %108
    vec4 out_texcoord0 = v107;  // output texcoord0 = %107
    vec4 out_texcoord1 = v107;  // output texcoord1 = %107
    vec4 out_texcoord2 = v105;  // output texcoord2 = %105
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = out_texcoord1;
    vary_texcoord2 = out_texcoord2;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
