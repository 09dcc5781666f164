// phong.fx technique PerPixelPhong_ps11, lowered for geforce3
// pass 1 of 2: Diffuse
#version 330 core
// vertex shader for IR program 44f70f4ffd2530c7
in vec4 attr_position;
in vec4 attr_texcoord0;
in vec4 attr_tangent;
in vec4 attr_normal;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c4;
uniform vec4 u_vs_c5;
uniform vec4 u_vs_c6;
uniform vec4 u_vs_c7;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c8;
uniform vec4 u_vs_c12;
uniform vec4 u_vs_c11;
uniform vec4 u_vs_c10;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_color1;
out vec4 vary_texcoord0;
out vec4 vary_texcoord3;

void main() {
#line 19
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c0;  // %1 = input vs_c0
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c1;  // %3 = input vs_c1
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c2;  // %6 = input vs_c2
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c3;  // %9 = input vs_c3
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = attr_texcoord0;  // %13 = input texcoord0
    vec4 v14 = vec4(v13.x, v13.y, v12.z, v12.w);  // %14 = merge %12, %13 mask=xy
    vec4 v15 = u_vs_c4;  // %15 = input vs_c4
    vec4 v16 = vec4(dot(v0, v15));  // %16 = dp4 %0, %15
    vec4 v17 = u_vs_c5;  // %17 = input vs_c5
    vec4 v18 = vec4(dot(v0, v17));  // %18 = dp4 %0, %17
    vec4 v19 = vec4(v16.x, v18.y, v16.z, v16.w);  // %19 = merge %16, %18 mask=y
    vec4 v20 = u_vs_c6;  // %20 = input vs_c6
    vec4 v21 = vec4(dot(v0, v20));  // %21 = dp4 %0, %20
    vec4 v22 = vec4(v19.x, v19.y, v21.z, v19.w);  // %22 = merge %19, %21 mask=z
    vec4 v23 = u_vs_c7;  // %23 = input vs_c7
    vec4 v24 = vec4(dot(v0, v23));  // %24 = dp4 %0, %23
    vec4 v25 = vec4(v22.x, v22.y, v22.z, v24.w);  // %25 = merge %22, %24 mask=w
    vec4 v26 = vec4(0.0, 0.0, 0.0, 0.0);  // %26 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v27 = attr_tangent;  // %27 = input tangent
    vec4 v28 = vec4(dot(v27.xyz, v15.xyz));  // %28 = dp3 %27, %15
    vec4 v29 = vec4(dot(v27.xyz, v17.xyz));  // %29 = dp3 %27, %17
    vec4 v30 = vec4(v28.x, v29.y, v28.z, v28.w);  // %30 = merge %28, %29 mask=y
    vec4 v31 = vec4(dot(v27.xyz, v20.xyz));  // %31 = dp3 %27, %20
    vec4 v32 = vec4(v30.x, v30.y, v31.z, v30.w);  // %32 = merge %30, %31 mask=z
    vec4 v33 = vec4(v32.x, v32.y, v32.z, v26.w);  // %33 = merge %26, %32 mask=xyz
    vec4 v34 = attr_normal;  // %34 = input normal
    vec4 v35 = vec4(dot(v34.xyz, v15.xyz));  // %35 = dp3 %34, %15
    vec4 v36 = vec4(dot(v34.xyz, v17.xyz));  // %36 = dp3 %34, %17
    vec4 v37 = vec4(v35.x, v36.y, v35.z, v35.w);  // %37 = merge %35, %36 mask=y
    vec4 v38 = vec4(dot(v34.xyz, v20.xyz));  // %38 = dp3 %34, %20
    vec4 v39 = vec4(v37.x, v37.y, v38.z, v37.w);  // %39 = merge %37, %38 mask=z
    vec4 v40 = vec4(v39.x, v39.y, v39.z, v26.w);  // %40 = merge %26, %39 mask=xyz
    vec4 v41 = v40.yzxx;  // %41 = swizzle %40 pattern=yzxx
    vec4 v42 = v33.zxyy;  // %42 = swizzle %33 pattern=zxyy
    vec4 v43 = (v41 * v42);  // %43 = mul %41, %42
    vec4 v44 = vec4(v43.x, v43.y, v43.z, v26.w);  // %44 = merge %26, %43 mask=xyz
    vec4 v45 = v40.zxyy;  // %45 = swizzle %40 pattern=zxyy
    vec4 v46 = (-v45);  // %46 = neg %45
    vec4 v47 = v33.yzxx;  // %47 = swizzle %33 pattern=yzxx
    vec4 v48 = (v46 * v47 + v44);  // %48 = mad %46, %47, %44
    vec4 v49 = vec4(v48.x, v48.y, v48.z, v44.w);  // %49 = merge %44, %48 mask=xyz
    vec4 v50 = u_vs_c9;  // %50 = input vs_c9
    vec4 v51 = (v50 - v25);  // %51 = sub %50, %25
    vec4 v52 = vec4(dot(v51.xyz, v51.xyz));  // %52 = dp3 %51, %51
    vec4 v53 = vec4(v51.x, v51.y, v51.z, v52.w);  // %53 = merge %51, %52 mask=w
    vec4 v54 = v53.wwww;  // %54 = swizzle %53 pattern=wwww
    vec4 v55 = mix(inversesqrt(abs(v54)), vec4(uintBitsToFloat(0x7F800000u)), equal(v54, vec4(0.0)));  // %55 = rsq %54
    vec4 v56 = vec4(v55.x, v26.y, v26.z, v26.w);  // %56 = merge %26, %55 mask=x
    vec4 v57 = v56.xxxx;  // %57 = swizzle %56 pattern=xxxx
    vec4 v58 = (v53 * v57);  // %58 = mul %53, %57
    vec4 v59 = vec4(v58.x, v58.y, v58.z, v53.w);  // %59 = merge %53, %58 mask=xyz
    vec4 v60 = u_vs_c8;  // %60 = input vs_c8
    vec4 v61 = (v60 - v25);  // %61 = sub %60, %25
    vec4 v62 = vec4(dot(v61.xyz, v61.xyz));  // %62 = dp3 %61, %61
    vec4 v63 = vec4(v61.x, v61.y, v61.z, v62.w);  // %63 = merge %61, %62 mask=w
    vec4 v64 = v63.wwww;  // %64 = swizzle %63 pattern=wwww
    vec4 v65 = mix(inversesqrt(abs(v64)), vec4(uintBitsToFloat(0x7F800000u)), equal(v64, vec4(0.0)));  // %65 = rsq %64
    vec4 v66 = vec4(v56.x, v65.y, v56.z, v56.w);  // %66 = merge %56, %65 mask=y
    vec4 v67 = v66.yyyy;  // %67 = swizzle %66 pattern=yyyy
    vec4 v68 = (v63 * v67);  // %68 = mul %63, %67
    vec4 v69 = vec4(v68.x, v68.y, v68.z, v63.w);  // %69 = merge %63, %68 mask=xyz
    vec4 v70 = (v69 + v59);  // %70 = add %69, %59
    vec4 v71 = vec4(v70.x, v70.y, v70.z, v69.w);  // %71 = merge %69, %70 mask=xyz
    vec4 v72 = vec4(dot(v71.xyz, v71.xyz));  // %72 = dp3 %71, %71
    vec4 v73 = vec4(v71.x, v71.y, v71.z, v72.w);  // %73 = merge %71, %72 mask=w
    vec4 v74 = v73.wwww;  // %74 = swizzle %73 pattern=wwww
    vec4 v75 = mix(inversesqrt(abs(v74)), vec4(uintBitsToFloat(0x7F800000u)), equal(v74, vec4(0.0)));  // %75 = rsq %74
    vec4 v76 = vec4(v66.x, v66.y, v75.z, v66.w);  // %76 = merge %66, %75 mask=z
    vec4 v77 = v76.zzzz;  // %77 = swizzle %76 pattern=zzzz
    vec4 v78 = (v73 * v77);  // %78 = mul %73, %77
    vec4 v79 = vec4(v78.x, v78.y, v78.z, v73.w);  // %79 = merge %73, %78 mask=xyz
    vec4 v80 = vec4(dot(v59.xyz, v33.xyz));  // %80 = dp3 %59, %33
    vec4 v81 = vec4(v80.x, v26.y, v26.z, v26.w);  // %81 = merge %26, %80 mask=x
    vec4 v82 = vec4(dot(v59.xyz, v49.xyz));  // %82 = dp3 %59, %49
    vec4 v83 = vec4(v81.x, v82.y, v81.z, v81.w);  // %83 = merge %81, %82 mask=y
    vec4 v84 = vec4(dot(v59.xyz, v40.xyz));  // %84 = dp3 %59, %40
    vec4 v85 = vec4(v83.x, v83.y, v84.z, v83.w);  // %85 = merge %83, %84 mask=z
    vec4 v86 = v85.xyzz;  // %86 = swizzle %85 pattern=xyzz
    vec4 v87 = vec4(0.5, 0.5, 0.5, 0.5);  // %87 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v88 = (v86 * v87 + v87);  // %88 = mad %86, %87, %87
    vec4 v89 = vec4(1.0, 1.0, 1.0, 1.0);  // %89 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v90 = vec4(v88.x, v88.y, v88.z, v89.w);  // %90 = merge %89, %88 mask=xyz
    vec4 v91 = vec4(v85.x, v85.y, v85.z, v12.w);  // %91 = merge %12, %85 mask=xyz
    vec4 v92 = vec4(dot(v79.xyz, v33.xyz));  // %92 = dp3 %79, %33
    vec4 v93 = vec4(v92.x, v26.y, v26.z, v26.w);  // %93 = merge %26, %92 mask=x
    vec4 v94 = vec4(dot(v79.xyz, v49.xyz));  // %94 = dp3 %79, %49
    vec4 v95 = vec4(v93.x, v94.y, v93.z, v93.w);  // %95 = merge %93, %94 mask=y
    vec4 v96 = vec4(dot(v79.xyz, v40.xyz));  // %96 = dp3 %79, %40
    vec4 v97 = vec4(v95.x, v95.y, v96.z, v95.w);  // %97 = merge %95, %96 mask=z
    vec4 v98 = vec4(v97.x, v97.y, v97.z, v12.w);  // %98 = merge %12, %97 mask=xyz
    vec4 v99 = u_vs_c12;  // %99 = input vs_c12
    vec4 v100 = v99.xxxx;  // %100 = swizzle %99 pattern=xxxx
    vec4 v101 = v59.wwww;  // %101 = swizzle %59 pattern=wwww
    vec4 v102 = (v100 * v101);  // %102 = mul %100, %101
    vec4 v103 = vec4(v102.x, v26.y, v26.z, v26.w);  // %103 = merge %26, %102 mask=x
    vec4 v104 = v103.xxxx;  // %104 = swizzle %103 pattern=xxxx
    vec4 v105 = u_vs_c11;  // %105 = input vs_c11
    vec4 v106 = v105.xxxx;  // %106 = swizzle %105 pattern=xxxx
    vec4 v107 = (v104 + v106);  // %107 = add %104, %106
    vec4 v108 = vec4(v107.x, v103.y, v103.z, v103.w);  // %108 = merge %103, %107 mask=x
    vec4 v109 = v108.xxxx;  // %109 = swizzle %108 pattern=xxxx
    vec4 v110 = mix(1.0 / v109, vec4(uintBitsToFloat(0x7F800000u)), equal(v109, vec4(0.0)));  // %110 = rcp %109
    vec4 v111 = vec4(v110.x, v108.y, v108.z, v108.w);  // %111 = merge %108, %110 mask=x
    vec4 v112 = u_vs_c10;  // %112 = input vs_c10
    vec4 v113 = v111.xxxx;  // %113 = swizzle %111 pattern=xxxx
    vec4 v114 = (v112 * v113);  // %114 = mul %112, %113
    vec4 v115 = clamp(v90, 0.0, 1.0);  // %115 = saturate %90
    vec4 v116 = clamp(v114, 0.0, 1.0);  // %116 = saturate %114
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v115;  // output color0 = %115
    vec4 out_color1 = v116;  // output color1 = %116
    vec4 out_texcoord0 = v14;  // output texcoord0 = %14
    vec4 out_texcoord1 = v91;  // output texcoord1 = %91
    vec4 out_texcoord2 = v98;  // output texcoord2 = %98
    vec4 out_texcoord3 = v14;  // output texcoord3 = %14
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_color1 = clamp(out_color1, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord3 = out_texcoord3;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
// pass 2 of 2: Specular
#version 330 core
// vertex shader for IR program 44f70f4ffd2530c7
in vec4 attr_position;
in vec4 attr_texcoord0;
in vec4 attr_tangent;
in vec4 attr_normal;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c4;
uniform vec4 u_vs_c5;
uniform vec4 u_vs_c6;
uniform vec4 u_vs_c7;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c8;
uniform vec4 u_vs_c12;
uniform vec4 u_vs_c11;
uniform vec4 u_vs_c10;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color1;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;
out vec4 vary_texcoord2;
out vec4 vary_texcoord3;

void main() {
#line 19
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c0;  // %1 = input vs_c0
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c1;  // %3 = input vs_c1
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c2;  // %6 = input vs_c2
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c3;  // %9 = input vs_c3
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = attr_texcoord0;  // %13 = input texcoord0
    vec4 v14 = vec4(v13.x, v13.y, v12.z, v12.w);  // %14 = merge %12, %13 mask=xy
    vec4 v15 = u_vs_c4;  // %15 = input vs_c4
    vec4 v16 = vec4(dot(v0, v15));  // %16 = dp4 %0, %15
    vec4 v17 = u_vs_c5;  // %17 = input vs_c5
    vec4 v18 = vec4(dot(v0, v17));  // %18 = dp4 %0, %17
    vec4 v19 = vec4(v16.x, v18.y, v16.z, v16.w);  // %19 = merge %16, %18 mask=y
    vec4 v20 = u_vs_c6;  // %20 = input vs_c6
    vec4 v21 = vec4(dot(v0, v20));  // %21 = dp4 %0, %20
    vec4 v22 = vec4(v19.x, v19.y, v21.z, v19.w);  // %22 = merge %19, %21 mask=z
    vec4 v23 = u_vs_c7;  // %23 = input vs_c7
    vec4 v24 = vec4(dot(v0, v23));  // %24 = dp4 %0, %23
    vec4 v25 = vec4(v22.x, v22.y, v22.z, v24.w);  // %25 = merge %22, %24 mask=w
    vec4 v26 = vec4(0.0, 0.0, 0.0, 0.0);  // %26 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v27 = attr_tangent;  // %27 = input tangent
    vec4 v28 = vec4(dot(v27.xyz, v15.xyz));  // %28 = dp3 %27, %15
    vec4 v29 = vec4(dot(v27.xyz, v17.xyz));  // %29 = dp3 %27, %17
    vec4 v30 = vec4(v28.x, v29.y, v28.z, v28.w);  // %30 = merge %28, %29 mask=y
    vec4 v31 = vec4(dot(v27.xyz, v20.xyz));  // %31 = dp3 %27, %20
    vec4 v32 = vec4(v30.x, v30.y, v31.z, v30.w);  // %32 = merge %30, %31 mask=z
    vec4 v33 = vec4(v32.x, v32.y, v32.z, v26.w);  // %33 = merge %26, %32 mask=xyz
    vec4 v34 = attr_normal;  // %34 = input normal
    vec4 v35 = vec4(dot(v34.xyz, v15.xyz));  // %35 = dp3 %34, %15
    vec4 v36 = vec4(dot(v34.xyz, v17.xyz));  // %36 = dp3 %34, %17
    vec4 v37 = vec4(v35.x, v36.y, v35.z, v35.w);  // %37 = merge %35, %36 mask=y
    vec4 v38 = vec4(dot(v34.xyz, v20.xyz));  // %38 = dp3 %34, %20
    vec4 v39 = vec4(v37.x, v37.y, v38.z, v37.w);  // %39 = merge %37, %38 mask=z
    vec4 v40 = vec4(v39.x, v39.y, v39.z, v26.w);  // %40 = merge %26, %39 mask=xyz
    vec4 v41 = v40.yzxx;  // %41 = swizzle %40 pattern=yzxx
    vec4 v42 = v33.zxyy;  // %42 = swizzle %33 pattern=zxyy
    vec4 v43 = (v41 * v42);  // %43 = mul %41, %42
    vec4 v44 = vec4(v43.x, v43.y, v43.z, v26.w);  // %44 = merge %26, %43 mask=xyz
    vec4 v45 = v40.zxyy;  // %45 = swizzle %40 pattern=zxyy
    vec4 v46 = (-v45);  // %46 = neg %45
    vec4 v47 = v33.yzxx;  // %47 = swizzle %33 pattern=yzxx
    vec4 v48 = (v46 * v47 + v44);  // %48 = mad %46, %47, %44
    vec4 v49 = vec4(v48.x, v48.y, v48.z, v44.w);  // %49 = merge %44, %48 mask=xyz
    vec4 v50 = u_vs_c9;  // %50 = input vs_c9
    vec4 v51 = (v50 - v25);  // %51 = sub %50, %25
    vec4 v52 = vec4(dot(v51.xyz, v51.xyz));  // %52 = dp3 %51, %51
    vec4 v53 = vec4(v51.x, v51.y, v51.z, v52.w);  // %53 = merge %51, %52 mask=w
    vec4 v54 = v53.wwww;  // %54 = swizzle %53 pattern=wwww
    vec4 v55 = mix(inversesqrt(abs(v54)), vec4(uintBitsToFloat(0x7F800000u)), equal(v54, vec4(0.0)));  // %55 = rsq %54
    vec4 v56 = vec4(v55.x, v26.y, v26.z, v26.w);  // %56 = merge %26, %55 mask=x
    vec4 v57 = v56.xxxx;  // %57 = swizzle %56 pattern=xxxx
    vec4 v58 = (v53 * v57);  // %58 = mul %53, %57
    vec4 v59 = vec4(v58.x, v58.y, v58.z, v53.w);  // %59 = merge %53, %58 mask=xyz
    vec4 v60 = u_vs_c8;  // %60 = input vs_c8
    vec4 v61 = (v60 - v25);  // %61 = sub %60, %25
    vec4 v62 = vec4(dot(v61.xyz, v61.xyz));  // %62 = dp3 %61, %61
    vec4 v63 = vec4(v61.x, v61.y, v61.z, v62.w);  // %63 = merge %61, %62 mask=w
    vec4 v64 = v63.wwww;  // %64 = swizzle %63 pattern=wwww
    vec4 v65 = mix(inversesqrt(abs(v64)), vec4(uintBitsToFloat(0x7F800000u)), equal(v64, vec4(0.0)));  // %65 = rsq %64
    vec4 v66 = vec4(v56.x, v65.y, v56.z, v56.w);  // %66 = merge %56, %65 mask=y
    vec4 v67 = v66.yyyy;  // %67 = swizzle %66 pattern=yyyy
    vec4 v68 = (v63 * v67);  // %68 = mul %63, %67
    vec4 v69 = vec4(v68.x, v68.y, v68.z, v63.w);  // %69 = merge %63, %68 mask=xyz
    vec4 v70 = (v69 + v59);  // %70 = add %69, %59
    vec4 v71 = vec4(v70.x, v70.y, v70.z, v69.w);  // %71 = merge %69, %70 mask=xyz
    vec4 v72 = vec4(dot(v71.xyz, v71.xyz));  // %72 = dp3 %71, %71
    vec4 v73 = vec4(v71.x, v71.y, v71.z, v72.w);  // %73 = merge %71, %72 mask=w
    vec4 v74 = v73.wwww;  // %74 = swizzle %73 pattern=wwww
    vec4 v75 = mix(inversesqrt(abs(v74)), vec4(uintBitsToFloat(0x7F800000u)), equal(v74, vec4(0.0)));  // %75 = rsq %74
    vec4 v76 = vec4(v66.x, v66.y, v75.z, v66.w);  // %76 = merge %66, %75 mask=z
    vec4 v77 = v76.zzzz;  // %77 = swizzle %76 pattern=zzzz
    vec4 v78 = (v73 * v77);  // %78 = mul %73, %77
    vec4 v79 = vec4(v78.x, v78.y, v78.z, v73.w);  // %79 = merge %73, %78 mask=xyz
    vec4 v80 = vec4(dot(v59.xyz, v33.xyz));  // %80 = dp3 %59, %33
    vec4 v81 = vec4(v80.x, v26.y, v26.z, v26.w);  // %81 = merge %26, %80 mask=x
    vec4 v82 = vec4(dot(v59.xyz, v49.xyz));  // %82 = dp3 %59, %49
    vec4 v83 = vec4(v81.x, v82.y, v81.z, v81.w);  // %83 = merge %81, %82 mask=y
    vec4 v84 = vec4(dot(v59.xyz, v40.xyz));  // %84 = dp3 %59, %40
    vec4 v85 = vec4(v83.x, v83.y, v84.z, v83.w);  // %85 = merge %83, %84 mask=z
    vec4 v86 = v85.xyzz;  // %86 = swizzle %85 pattern=xyzz
    vec4 v87 = vec4(0.5, 0.5, 0.5, 0.5);  // %87 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v88 = (v86 * v87 + v87);  // %88 = mad %86, %87, %87
    vec4 v89 = vec4(1.0, 1.0, 1.0, 1.0);  // %89 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v90 = vec4(v88.x, v88.y, v88.z, v89.w);  // %90 = merge %89, %88 mask=xyz
    vec4 v91 = vec4(v85.x, v85.y, v85.z, v12.w);  // %91 = merge %12, %85 mask=xyz
    vec4 v92 = vec4(dot(v79.xyz, v33.xyz));  // %92 = dp3 %79, %33
    vec4 v93 = vec4(v92.x, v26.y, v26.z, v26.w);  // %93 = merge %26, %92 mask=x
    vec4 v94 = vec4(dot(v79.xyz, v49.xyz));  // %94 = dp3 %79, %49
    vec4 v95 = vec4(v93.x, v94.y, v93.z, v93.w);  // %95 = merge %93, %94 mask=y
    vec4 v96 = vec4(dot(v79.xyz, v40.xyz));  // %96 = dp3 %79, %40
    vec4 v97 = vec4(v95.x, v95.y, v96.z, v95.w);  // %97 = merge %95, %96 mask=z
    vec4 v98 = vec4(v97.x, v97.y, v97.z, v12.w);  // %98 = merge %12, %97 mask=xyz
    vec4 v99 = u_vs_c12;  // %99 = input vs_c12
    vec4 v100 = v99.xxxx;  // %100 = swizzle %99 pattern=xxxx
    vec4 v101 = v59.wwww;  // %101 = swizzle %59 pattern=wwww
    vec4 v102 = (v100 * v101);  // %102 = mul %100, %101
    vec4 v103 = vec4(v102.x, v26.y, v26.z, v26.w);  // %103 = merge %26, %102 mask=x
    vec4 v104 = v103.xxxx;  // %104 = swizzle %103 pattern=xxxx
    vec4 v105 = u_vs_c11;  // %105 = input vs_c11
    vec4 v106 = v105.xxxx;  // %106 = swizzle %105 pattern=xxxx
    vec4 v107 = (v104 + v106);  // %107 = add %104, %106
    vec4 v108 = vec4(v107.x, v103.y, v103.z, v103.w);  // %108 = merge %103, %107 mask=x
    vec4 v109 = v108.xxxx;  // %109 = swizzle %108 pattern=xxxx
    vec4 v110 = mix(1.0 / v109, vec4(uintBitsToFloat(0x7F800000u)), equal(v109, vec4(0.0)));  // %110 = rcp %109
    vec4 v111 = vec4(v110.x, v108.y, v108.z, v108.w);  // %111 = merge %108, %110 mask=x
    vec4 v112 = u_vs_c10;  // %112 = input vs_c10
    vec4 v113 = v111.xxxx;  // %113 = swizzle %111 pattern=xxxx
    vec4 v114 = (v112 * v113);  // %114 = mul %112, %113
    vec4 v115 = clamp(v90, 0.0, 1.0);  // %115 = saturate %90
    vec4 v116 = clamp(v114, 0.0, 1.0);  // %116 = saturate %114
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v115;  // output color0 = %115
    vec4 out_color1 = v116;  // output color1 = %116
    vec4 out_texcoord0 = v14;  // output texcoord0 = %14
    vec4 out_texcoord1 = v91;  // output texcoord1 = %91
    vec4 out_texcoord2 = v98;  // output texcoord2 = %98
    vec4 out_texcoord3 = v14;  // output texcoord3 = %14
#line 10000
    vary_color1 = clamp(out_color1, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = out_texcoord1;
    vary_texcoord2 = out_texcoord2;
    vary_texcoord3 = out_texcoord3;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
