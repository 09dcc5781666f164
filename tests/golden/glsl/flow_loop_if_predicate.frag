#version 330 core
// fragment shader for IR program 79cddf811914c8b9
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
    vec4 builtin_vpos = vec4(floor(gl_FragCoord.xy), 0.0, 1.0);
#line 3
    vec4 v0 = vec4(0.5, 0.5, 0.5, 1.0);  // %0 = const (0.5, 0.5, 0.5, 1.0)
    vec4 v1 = vec4(0.0, 0.0, 0.0, 0.0);  // %1 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v2 = builtin_vpos;  // %2 = input vpos
    vec4 v3 = v2.xxxx;  // %3 = swizzle %2 pattern=xxxx
    vec4 v4 = vec4(4.0, 4.0, 4.0, 4.0);  // %4 = const (4.0, 4.0, 4.0, 4.0)
    vec4 v5 = vec4(lessThan(v3, v4));  // %5 = slt %3, %4
    vec4 v6 = v0;  // %6 = var %0
    vec4 v7 = v1;  // %7 = var %1
    for (int loop0 = 0; loop0 < 2; ++loop0) {  // loop count=2
        vec4 v8 = v6.xxxx;  // %8 = swizzle %6 pattern=xxxx
        vec4 v9 = v7.xxxx;  // %9 = swizzle %7 pattern=xxxx
        vec4 v10 = (v9 + v1);  // %10 = add %9, %1
        vec4 v11 = (v10 - v1);  // %11 = sub %10, %1
        vec4 v12 = abs(v11);  // %12 = abs %11
        vec4 v13 = (-v12);  // %13 = neg %12
        vec4 v14 = vec4(1.0, 0.0, 0.0, 0.0);  // %14 = const (1.0, 0.0, 0.0, 0.0)
        vec4 v15 = mix(v1, v14, greaterThanEqual(v13, vec4(0.0)));  // %15 = cmp %13, %14, %1
        vec4 v16 = vec4(1.0, 1.0, 1.0, 1.0);  // %16 = const (1.0, 1.0, 1.0, 1.0)
        vec4 v17 = (v10 - v16);  // %17 = sub %10, %16
        vec4 v18 = abs(v17);  // %18 = abs %17
        vec4 v19 = (-v18);  // %19 = neg %18
        vec4 v20 = mix(v15, v0, greaterThanEqual(v19, vec4(0.0)));  // %20 = cmp %19, %0, %15
        vec4 v21 = v20.xxxx;  // %21 = swizzle %20 pattern=xxxx
        vec4 v22 = (v8 + v21);  // %22 = add %8, %21
        vec4 v23 = vec4(v22.x, v6.y, v6.z, v6.w);  // %23 = merge %6, %22 mask=x
        v6 = v23;  // assign %6, %23
        vec4 v24 = v6.xxxx;  // %24 = swizzle %6 pattern=xxxx
        vec4 v25 = v2.yyyy;  // %25 = swizzle %2 pattern=yyyy
        vec4 v26 = vec4(greaterThanEqual(v24, v25));  // %26 = sge %24, %25
        if (v26.x != 0.0) break;  // break %26
        vec4 v27 = (v7 + v16);  // %27 = add %7, %16
        v7 = v27;  // assign %7, %27
    }  // endloop
    if (v5.x != 0.0) {  // if %5
        vec4 v28 = v6.yyyy;  // %28 = swizzle %6 pattern=yyyy
        vec4 v29 = vec4(1.0, 1.0, 1.0, 1.0);  // %29 = const (1.0, 1.0, 1.0, 1.0)
        vec4 v30 = (v28 * v29);  // %30 = mul %28, %29
        vec4 v31 = vec4(v6.x, v30.y, v6.z, v6.w);  // %31 = merge %6, %30 mask=y
        vec4 v32 = vec4(0.5, 0.5, 0.5, 0.5);  // %32 = const (0.5, 0.5, 0.5, 0.5)
        vec4 v33 = (v5 - v32);  // %33 = sub %5, %32
        vec4 v34 = mix(v6, v31, greaterThanEqual(v33, vec4(0.0)));  // %34 = cmp %33, %31, %6
        v6 = v34;  // assign %6, %34
    } else {  // else
        vec4 v35 = (-v0);  // %35 = neg %0
        if (any(lessThan(v35.xyzw, vec4(0.0)))) discard;  // kill %35
    }  // endif
    vec4 out_color0 = v6;  // output color0 = %6
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
