"""Direct3D assembly: the seed listings assemble and validate; parsing details; stats by hand.

Listings are copied from Boyd and Taylor, "Hardware Shading with Direct3D" (DX8 vs.1.1 /
ps.1.1), and Persson, "Fragment level Phong illumination" (vs.2.0 / ps.2.0). Changes to a
listing are marked `FIX:` with the reason.
"""
from __future__ import annotations

import pytest

from effects.shaders.asm import INSTRUCTIONS, VERSIONS, assemble, check, lookup
from effects.base.errors import Location
from effects.model import ShaderBlock, VertexDeclElement

LOC = Location("t.fx", 10, 9)


def block(src: str, stage: str = "pixel", decl=None) -> ShaderBlock:
    return ShaderBlock(stage, None, src, decl=decl, location=LOC)


def assemble_clean(src: str, stage: str = "pixel", decl=None):
    prog = assemble(block(src, stage, decl))
    errors = check(prog)
    assert [str(e) for e in errors] == []
    return prog


# -- Boyd & Taylor, "Hardware Shading with Direct3D" -------------------------------------------

BRDF_DECL = tuple(VertexDeclElement(0, "float", r, 3) for r in (0, 3, 7, 8))

BOYD_BRDF_VS = """
            vs.1.1              // version number

            m4x4 oPos, v0, c4   // transform point to projection space
            m4x4 r4,v0,c0       // transform point to world space
            m3x3 r0,v3,c0       // transform Normal to World Space, result in r0
            m3x3 r1,v8,c0       // transform Tangent to World Space

            mul r2,-r1.zxyw,r0.yzxw;   // comptue binorm with cross product
            mad r2,-r1.yzxw,r0.zxyw,-r2;

            // get negative view vector
            add r4.xyz,-r4.xyz,c10
            dp3 r5.x,r4.xyz,r4.xyz
            rsq r5.x,r5.x
            mul r4.xyz,r5.xxx,r4.xyz

            //compute the half angle and normalize
            add r5.xyz,r4.xyz,-c16
            dp3 r6.x,r5.xyz,r5.xyz
            rsq r6.x,r6.x
            mul r5.xyz,r6.xxx,r5.xyz

            //t0 = view
            dp3 oT0.x,r4,r1
            dp3 oT0.y,r4,r2
            dp3 oT0.z,r4,r0

            //t1 = -light
            dp3 oT1.x,-c16,r1
            dp3 oT1.y,-c16,r2
            dp3 oT1.z,-c16,r0   // FIX: the listing writes oT2.z here, plainly meant oT1.z

            //t2 = half angle
            dp3 oT2.x,r5,r1
            dp3 oT2.y,r5,r2
            dp3 oT2.z,r5,r0

            //object might have its own texture
            mov oT3.xy,v7.xy

            //move diffuse color in
            mov oD0,c9
"""

BOYD_BRDF_PS = """
            ps.1.1
            tex t0
            tex t1
            tex t2
            tex t3

            mul r0,t0,t1 // combine 1 st  2 brdf  factors
            mul r0,r0,t2 // multiply in 3 rd  fa ctor
            mul r0,r0,t3 // apply detail texture
            mul r0,r0,v0 // light using diffuse primary color
"""

# FIX: a fragment without version or position write; completed with both to validate it.
BOYD_TANGENT_FRAGMENT_VS = """vs.1.1
m4x4 oPos, v0, c4   // FIX: added so the fragment is a whole shader
// v3 is normal vector
// v8 is tangent vector
// c0-c3 is World Transform
// c12 is light dir

//tangent space basis generation
m3x3 r3,v8,c0      // transform tan to world space
m3x3 r5,v3,c0      // transform norm to world space

mul r0,r3.zxyw,r5.yzxw   // cross prod to generate binormal
mad r4,r3.yzxw,r5.zxyw,-r0

dp3 r6.x,r3,-c12      // transform the light vector,
dp3 r6.y,r4,-c12      // by resulting matrix
dp3 r6.z,r5,-c12      // r6 is light dir in tan space
"""

BOYD_DIFFUSE_VS = """//v0 = position
//v3 = normal (also the w vector)
//v7 = texture coordinate
//v8 = tangent (u vector)

vs.1.1

//tranform position
m4x4 oPos,v0,c4

//tsb generation
m3x3 r3,v8,c0         //gen normal
m3x3 r5,v3,c0         //gen tangent

//gen binormal via Cross product
mul r0,-r3.zxyw,r5.yzxw;
mad r4,-r3.yzxw,r5.zxyw,-r0;

//diffuse, transform the light vector
dp3 r6.x,r3,-c16
dp3 r6.y,r4,-c16
dp3 r6.z,r5,-c16

//light in oD0
mad oD0.xyz,r6.xyz,c20,c20   //multiply by a half then add half

//tex coords
mov oT0.xy, v7.xy
mov oT1.xy, v7.xy
"""

BOYD_DIFFUSE_PS = """ps.1.1

tex t0                  //sample texture
tex t1                  //sample normal

//diffuse
dp3_sat r1,t1_bx2,v0_bx2         //dot(normal,light)

//assemble final color
mul r0,t0,    r1            //modulate against base color
"""

BOYD_EMBOSS_VS = """//v0 = position
vs.1.1         // for emboss

m4x4 oPos, v0,c08      // generate output position

//diffuse
m3x3 r3, v8, c0       // transform tan to world space
m3x3 r5, v3, c0      // transform norm to world space

mul r0,r3.zxyw,r5.yzxw  // cross prod to generate binormal
mad r4,r3.yzxw,r5.zxyw,-r0

dp3 r6.x,r3,c12      // tangent space light in r6
dp3 r6.y,r4,c12
//   dp3 r6.z,r5,c12  don't need this
//                    -only x and y shifts matter

// set up the texture, based on light direction:
mul r1.xy,  r6.xy, -c24.xy
mov oT0.xy, v7.xy         // copy the base height map
add oT1.xy, v7.xy,  r1.xy    // offset the normal height map

// simple dot product to get global darkening effects:
dp3 oD0.xyz,v3.xyz,c12.xyz
"""

BOYD_SPECULAR_VS = """vs.1.1

//tranform position
m4x4 oPos,v0,c4

//tsb generation
m3x3 r3,v8,c0            //gen normal
m3x3 r5,v3,c0            //gen tangent

//gen binormal via Cross product
mul r0,-r3.zxyw,r5.yzxw;
mad r4,-r3.yzxw,r5.zxyw,-r0;

//specular
m4x4 r2,v0,c0            //transform position
//get a vector toward the camera
add r2,-r2,c24
dp3 r11.x,  r2.xyz,r2.xyz   //load the square into r11

rsq r11.xyz,r11.x         //get the inverse of the square
mul r2.xyz, r2.xyz,r11.xyz   //multiply, r0 = -(camera vector)
add r2.xyz,r2.xyz,-c16      //get half angle

//normalize
dp3 r11.x,r2.xyz,r2.xyz      //load the square into r1
rsq r11.xyz,r11.x         //get the inverse of the square
mul r2.xyz,r2.xyz,r11.xyz   //multiply, r2 = HalfAngle

//transform the half angle vector
dp3 r8.x,r3,r2
dp3 r8.y,r4,r2
dp3 r8.z,r5,r2

//half-angle in oD1
mad oD1.xyz,   r8.xyz,c20,c20   //mutiply by a half, add half

//tex coords
mov oT0.xy,   v7.xy
mov oT1.xy,   v7.xy
"""

BOYD_SPECULAR_PS = """ps.1.1            // pow2 by multiplies
tex t0            // color map
tex t1            // normal map

//  specular lighting dotproduct
dp3_sat r0,t1_bx2,v1_bx2   // bias t0 and v1 (light color)

mul r1,r0,r0            //  2nd power
mul r0,r1,r1            //  4th power
mul r1,r0,r0            //  8th power
mul r0,r1,r1            // 16th power!

//assemble final color
mul r0,r0,t0         // modulate by color map
"""

BOYD_TABLE_VS = """vs.1.1

//tranform position
m4x4 oPos,v0,c4

//tsb generation
m3x3 r3,v8,c0            //transform normal
m3x3 r5,v3,c0            //and tangent
//Cross product
mul r0,-r3.zxyw,r5.yzxw;
mad r4,-r3.yzxw,r5.zxyw,-r0;

//specular
m4x4 r2,v0,c0            //transform position

//get a vector toward the camera
add r2,-r2,c24

dp3 r11.x,r2.xyz,r2.xyz   //load the square into r11
rsq r11.xyz,r11.x         //get the inverse of the square
mul r2.xyz,r2.xyz,r11.xyz //multiply, r0 = -(camera vector)

add r2.xyz,r2.xyz,-c16    //get half angle

//normalize
dp3 r11.x,r2.xyz,r2.xyz   //load the square into r1
rsq r11.xyz,r11.x         //get the inverse of the square
mul r2.xyz,r2.xyz,r11.xyz //multiply, r2 = HalfAngle

//transform the half angle vector
dp3 r8.x,r3,r2
dp3 r8.y,r4,r2
dp3 r8.z,r5,r2

//tex coords
mov oT0.xy, v7.xy         //coord to samp normal from
mov oT1.xyz,r8            //Not a tex coord, but half

mov oT2.xyz,r8            //angle

mov oT3.xy, v7.xy
"""

BOYD_TABLE_PS = """ps.1.1         // exponentiation by table lookup

//  texcoord t1      // the diffuse light direction
//  texcoord t2      // half-angle vector
//  texture at stage t2 is a table lookup function

tex t0         // sample the normal map
texm3x2pad t1, t0_bx2     // 1st row of mult, 1st dotproduct=u
texm3x2tex t2, t0_bx2     // 2nd row of mult, 2nd dotproduct=v
tex t3         // FIX: the listing reads t3 (the colour map, stage 3) without sampling it

//asemble final color
mov r0,t2         // use (u,v) above to get intensity
mul r0,r0,t3            //blend terms
"""

BOYD_HEMISPHERE_VS = """vs.1.1         // vertex hemisphere shader

m4x4 oPos,v0,c8   // transform position
m3x3 r0, v3,c0   // transform normal

dp3 r0,r0,c40   // c40 is sky vector
mov r1,c33      // c33 is .5f in all channels
mad r0,r0,c33,r1   // bias operation

mov r1,c42      // c42 is ground color
sub r1,c41,r1      // c41 is sky color
mad r0,r1,r0,c42   // lerp operation

//c44 = (1,1,1,1)
sub r1,c44,v7.zzz   // v7.zzz = occlusion term
mul r0,r0,r1
mul oD0,r0,c43
"""

# FIX: a fragment without a version token; ps.1.1 added (the article's pixel shader version).
BOYD_HEMISPHERE_PS = """ps.1.1
//   v0.rgb is hemi axis in tangent space
// v0.a is occlusion ratio from vshader
tex t0         // normal map

tex t1         // base texture

dp3_d2_sat r0,v0_bx2,t0_bx2   // dot normal with hemi axis
add r0,r0,c5      // map into range, not _sat
lrp r0,r0,c1,c2
mul r0,r0,t1      // modulate base texture
"""

# -- Persson, "Fragment level Phong illumination" ---------------------------------------------

PERSSON_VS = """vs.2.0

dcl_position v0
dcl_texcoord0 v1 // TexCoord
dcl_texcoord1 v2 // uVec
dcl_texcoord2 v3 // vVec
dcl_texcoord3 v4 // normal

// c0-c3 =.mvp matrix
// c4 = camera position
// c5 = light position

// Transform position
m4x4 oPos, v0, c0

// Output texcoord
mov oT0, v1

sub r0, c5, v0 // r0 = light vector
dp3 oT1.x, r0, v2
dp3 oT1.y, r0, v3
dp3 oT1.z, r0, v4 // oT1 = light vector in tangent space

sub r1, c4, v0 // r1 = view vector
dp3 oT2.x, r1, v2
dp3 oT2.y, r1, v3
dp3 oT2.z, r1, v4 // oT2 = view vector in tangent space
"""

# The vertex shader with the shadow additions ("mov oT3, -r0" and three offset positions,
# with their defs placed after the declarations as a def must precede the instructions).
PERSSON_SHADOW_VS = PERSSON_VS.replace("// c0-c3 =.mvp matrix", """def c8, 1.0, 2.0, -1.0, 0.0
def c9, 2.0, -1.0, 1.0, 0.0
def c10, -1.0, 1.0, 2.0, 0.0
// c0-c3 =.mvp matrix""") + """
mov      oT3, -r0          // oT3 = shadow map
sub      oT4, c8,  r0
sub      oT5, c9,  r0
sub      oT6, c10, r0
"""

PERSSON_DIFFUSE_PS = """ps.2.0

dcl t0.xy
dcl t1

dcl_2d s0
dcl_2d s1

def c0, 2.0, 1.0, 0.0, 0.0 // (2.0, 1.0, unused ...)

texld    r0, t0, s0          // r0 = base
texld    r1, t0, s1          // r1 = bump

mad      r1.xyz, r1, c0.x, -c0.y // bump[0..1] => bump[-1..1]

dp3      r7.w, r1, r1
rsq      r7.w, r7.w
mul      r1.xyz, r1, r7.w    // r1 = post-filter normalized bumpmap

dp3      r7, t1, t1
rsq      r7.w, r7.x
mul      r3, t1, r7.w       // r3 = normalized light vector

dp3_sat  r4, r3, r1         // r4 = diffuse

mul      r4, r4, r0         // r4 = base * diffuse
mov      oC0, r4
"""

# The article builds the final pixel shader piece by piece ("inserted right after the light
# vector normalization", "..."); this is that shader put together: diffuse, attenuation,
# gloss-mapped specular, ambient and the four-sample shadow map (def c1 as last revised).
# FIX: the shadow def "def c1, 0.97, 1.0, 0.0, 0.0" was later revised to 0.25; only the
# revised one is kept (two defs of c1 would be redundant).
PERSSON_FINAL_PS = """ps.2.0
dcl t0.xy
dcl t1
dcl t2
dcl t3
dcl t4
dcl t5
dcl t6
dcl_2d s0
dcl_2d s1
dcl_2d s2
dcl_cube s3

def c0, 2.0, 1.0, 24.0, 0.0 // (2.0, 1.0, specular exponent, 0.0)
def      c1, 0.97, 0.25, 0.0, 0.0 // (biasfactor, averaging factors)

texld    r0, t0, s0          // r0 = base
texld    r1, t0, s1          // r1 = bump
texld r2, t0, s2 // r2 = gloss
texld    r8, t3, s3        // r8 = shadow map
texld    r9,  t4,  s3           // r9 = shadow map
texld    r10, t5,  s3          // r10 = shadow map
texld    r11, t6,  s3          // r11 = shadow map

mad      r1.xyz, r1, c0.x, -c0.y // bump[0..1] => bump[-1..1]

dp3      r7.w, r1, r1
rsq      r7.w, r7.w
mul      r1.xyz, r1, r7.w    // r1 = post-filter normalized bumpmap

dp3      r7, t1, t1
rsq      r7.w, r7.x
mul      r3, t1, r7.w       // r3 = normalized light vector
mul      r8.y, r7.x, c1.x // r8.y = lengthSqr(light vector) * biasfactor

// c2 = (constant attenuation, quadratic attenuation, ambient, unused)
mad      r5, c2.y, r7, c2.x
rcp      r5, r5.x           // r5 = attenuation

dp3_sat  r4, r3, r1         // r4 = diffuse

dp3 r7, t2, t2
rsq r7.w, r7.x
mul r6, t2, r7.w // r6 = normalized view vector

dp3 r7, r3, r1
mul r7, r7, c0.x
mad r3, r7, r1, -r3 // r3 = reflection vector

dp3_sat r3, r3, r6
pow r3, r3.x, c0.z // r3 = specular
mul r3, r3, r2 // r3 = specular * gloss

sub      r8.x, r8.x, r8.y
sub      r9.x, r9.x, r8.y
sub      r10.x, r10.x, r8.y
sub      r11.x, r11.x, r8.y

cmp      r8.x, r8.x, c1.y, c1.z
cmp      r9.x, r9.x, c1.y, c1.z
cmp      r10.x, r10.x, c1.y, c1.z
cmp      r11.x, r11.x, c1.y, c1.z

add      r8.x, r8.x, r9.x
add      r8.x, r8.x, r10.x
add      r8.x, r8.x, r11.x

mad      r4, r4, r0, r3      // r4 = base * diffuse + specular * gloss
mul      r4, r4, r5          // r4 *= attenuation
mul      r4, r4, r8.x        // r8 *= shadow factor
mad      r4, r0, c2.z, r4    // r4 += base * ambient
mov      oC0, r4
"""

PERSSON_DEPTH_VS = """vs.2.0

dcl_position v0
// c0-c3 = mvp matrix
// c5     = light position

// Transform position
m4x4      oPos, v0, c0

sub       oT0, c5, v0      // oT0 = light vector
"""

PERSSON_DEPTH_PS = """ps.2.0

dcl t0

dp3      r0, t0, t0
mov      oC0, r0
"""

SEEDS = [
    ("boyd brdf vs", BOYD_BRDF_VS, "vertex", BRDF_DECL, "vs_1_1"),
    ("boyd brdf ps", BOYD_BRDF_PS, "pixel", None, "ps_1_1"),
    ("boyd tangent fragment", BOYD_TANGENT_FRAGMENT_VS, "vertex", None, "vs_1_1"),
    ("boyd diffuse vs", BOYD_DIFFUSE_VS, "vertex", None, "vs_1_1"),
    ("boyd diffuse ps", BOYD_DIFFUSE_PS, "pixel", None, "ps_1_1"),
    ("boyd emboss vs", BOYD_EMBOSS_VS, "vertex", None, "vs_1_1"),
    ("boyd specular vs", BOYD_SPECULAR_VS, "vertex", None, "vs_1_1"),
    ("boyd specular ps", BOYD_SPECULAR_PS, "pixel", None, "ps_1_1"),
    ("boyd table vs", BOYD_TABLE_VS, "vertex", None, "vs_1_1"),
    ("boyd table ps", BOYD_TABLE_PS, "pixel", None, "ps_1_1"),
    ("boyd hemisphere vs", BOYD_HEMISPHERE_VS, "vertex", None, "vs_1_1"),
    ("boyd hemisphere ps", BOYD_HEMISPHERE_PS, "pixel", None, "ps_1_1"),
    ("persson vs", PERSSON_VS, "vertex", None, "vs_2_0"),
    ("persson shadow vs", PERSSON_SHADOW_VS, "vertex", None, "vs_2_0"),
    ("persson diffuse ps", PERSSON_DIFFUSE_PS, "pixel", None, "ps_2_0"),
    ("persson final ps", PERSSON_FINAL_PS, "pixel", None, "ps_2_0"),
    ("persson depth vs", PERSSON_DEPTH_VS, "vertex", None, "vs_2_0"),
    ("persson depth ps", PERSSON_DEPTH_PS, "pixel", None, "ps_2_0"),
]


@pytest.mark.parametrize("name,src,stage,decl,version", SEEDS, ids=[s[0] for s in SEEDS])
def test_seed_listing_assembles_and_validates(name, src, stage, decl, version):
    prog = assemble_clean(src, stage, decl)
    assert prog.name == version
    assert prog.instructions


# -- parsing details --------------------------------------------------------------------------

def test_version_spellings_are_equivalent():
    for text in ("ps.1.1", "ps_1_1", "PS.1.1", "Ps_1_1"):
        assert assemble(block(f"{text}\ntex t0\nmov r0, t0")).name == "ps_1_1"
    assert assemble(block("ps_2_a\ndcl t0\nmov oC0, t0")).name == "ps_2_a"
    assert assemble(block("ps.2.0\ndcl t0\nmov oC0, t0")).version == (2, 0)
    assert assemble(block("vs.3.0\ndcl_position o0\ndcl_position v0\nmov o0, v0",
                          "vertex")).kind == "vs"


def test_operands_modifiers_and_swizzles():
    prog = assemble(block("ps.1.4\ntexld r0, t0\nphase\nmul_x2_sat r0.rgb, 1-r0, -r0_bx2.a\n"
                          "+mov r0.a, r0_x2.b"))
    phase2 = prog.instructions[1]
    assert phase2.opcode == "mul" and phase2.shift == 1 and phase2.saturate
    assert phase2.phase == 2 and prog.instructions[0].phase == 1
    assert phase2.dst.mask == (0, 1, 2)
    a, b = phase2.srcs
    assert a.modifier == "invert" and not a.negate and a.swizzle == (0, 1, 2, 3)
    assert b.modifier == "bx2" and b.negate and b.swizzle == (3, 3, 3, 3)
    co = prog.instructions[2]
    assert co.coissue and co.dst.mask == (3,) and co.srcs[0].modifier == "x2"
    assert co.srcs[0].swizzle == (2, 2, 2, 2)
    assert check(prog) == []


def test_short_swizzle_repeats_its_last_component():
    prog = assemble(block("vs.1.1\nmov oPos, v0\nmov oT0.xy, v7.xy\nmov oT1, v1.wzx", "vertex"))
    assert prog.instructions[1].srcs[0].swizzle == (0, 1, 1, 1)
    assert prog.instructions[2].srcs[0].swizzle == (3, 2, 0, 0)


def test_relative_addressing_and_defs():
    prog = assemble(block("vs_1_1\ndcl_position v0\ndef c90, 1, -2.5, 0.5f, 3\n"
                          "mov a0.x, v0.x\nmov r0, c[a0.x + 5]\nmov oPos, r0", "vertex"))
    assert prog.defs == {90: (1.0, -2.5, 0.5, 3.0)}
    rel = prog.instructions[1].srcs[0]
    assert rel.kind == "c" and rel.index == 5 and rel.relative.kind == "a"
    assert rel.relative.component == 0
    assert check(prog) == []


def test_declarations():
    prog = assemble(block("ps_2_0\ndcl t0.xy\ndcl v1\ndcl_cube s3\ndcl_volume s1\n"
                          "texld r0, t0, s3\nmov oC0, r0"))
    kinds = [(d.register.name, d.sampler_type, d.register.mask) for d in prog.dcls]
    assert kinds == [("t0", None, (0, 1)), ("v1", None, None), ("s3", "cube", None),
                     ("s1", "volume", None)]
    vs = assemble(block("vs_2_0\ndcl_texcoord3 v4\ndcl_position v0\nmov oPos, v0", "vertex"))
    assert [(d.usage, d.usage_index) for d in vs.dcls] == [("texcoord", 3), ("position", 0)]


def test_comments_of_every_kind_and_free_form_lines():
    prog = assemble(block("ps.1.1 ; semicolon comment\n/* block\ncomment */ tex t0 "
                          "// slashes\nmov r0, t0 mul r0, r0, t0"))
    assert [i.opcode for i in prog.instructions] == ["tex", "mov", "mul"]
    assert prog.instructions[0].location == Location("t.fx", 12, 12)


def test_locations_are_file_positions():
    prog = assemble(block("ps.1.1\n  tex t0\nmov r0, t0"))
    assert prog.location == Location("t.fx", 10, 9)       # line 0 is offset by the column
    assert prog.instructions[0].location == Location("t.fx", 11, 3)
    assert prog.instructions[1].srcs[0].location == Location("t.fx", 12, 9)


def test_dx8_decl_block_declares_the_inputs():
    prog = assemble(block(BOYD_BRDF_VS, "vertex", BRDF_DECL))
    assert [d.register.name for d in prog.dcls if d.from_decl] == ["v0", "v3", "v7", "v8"]


def test_every_row_of_the_table_is_well_formed():
    names = {row.name for row in INSTRUCTIONS}
    for expected in ("add", "texm3x3spec", "texld", "bem", "dp2add", "sincos", "m4x4", "lit",
                     "expp", "mova", "dsx", "texldd", "phase", "def", "dcl", "if", "rep"):
        assert expected in names
    for row in INSTRUCTIONS:
        assert row.category in ("arith", "tex", "flow", "setup")
        assert row.formula and row.op
        assert set(row.operands) <= set("dsxSfnBlbILp")
        assert row.versions.names <= set(VERSIONS)


def test_per_version_slot_costs_from_the_docs():
    assert lookup("dp4", "ps_1_2").slot_cost("ps_1_2") == 2
    assert lookup("dp4", "ps_1_4").slot_cost("ps_1_4") == 1
    assert lookup("cmp", "ps_1_3").slot_cost("ps_1_3") == 2
    assert lookup("m4x4", "vs_1_1").slot_cost("vs_1_1") == 4
    assert lookup("m3x3", "ps_2_0").slot_cost("ps_2_0") == 3
    assert lookup("exp", "vs_1_1").slot_cost("vs_1_1") == 10
    assert lookup("exp", "vs_2_0").slot_cost("vs_2_0") == 1
    assert lookup("lrp", "ps_2_0").documented_cost("ps_2_0") == 2   # fxc counts 1: test_slot_costs
    assert lookup("lrp", "ps_1_1").slot_cost("ps_1_1") == 1
    assert lookup("texld", "ps_1_1") is None
    assert lookup("texld", "ps_1_4").operands == "ds"
    assert lookup("texld", "ps_2_0").operands == "dsS"


# -- stats, counted by hand -------------------------------------------------------------------

def test_stats_of_persson_diffuse_ps():
    s = assemble(block(PERSSON_DIFFUSE_PS)).stats
    # texld ×2; mad dp3 rsq mul dp3 rsq mul dp3 mul mov = 10 arithmetic
    assert (s.texture_slots, s.arithmetic_slots, s.total_slots) == (2, 10, 12)
    assert s.temps_used == 5                       # r0 r1 r3 r4 r7
    assert s.constants_used == 1                   # c0
    assert s.samplers_used == {0, 1} and s.texcoords_used == {0, 1}
    assert s.dependent_read_depth == 1
    assert not s.uses_arbitrary_swizzle and not s.uses_predication
    assert s.highest == {"t": 1, "s": 1, "c": 0, "r": 7, "oC": 0}


def test_stats_of_persson_final_ps():
    s = assemble(block(PERSSON_FINAL_PS)).stats
    # 7 texld; arithmetic: mad dp3 rsq mul (4) dp3 rsq mul mul (4) mad rcp (2) dp3 (1)
    # dp3 rsq mul (3) dp3 mul mad (3) dp3 pow=3 mul (5) sub×4 cmp×4 add×3 (11)
    # mad mul mul mad mov (5) = 38
    assert (s.texture_slots, s.arithmetic_slots) == (7, 38)
    assert s.temps_used == 12 and s.highest["r"] == 11
    assert s.samplers_used == {0, 1, 2, 3}


def test_stats_of_boyd_brdf_vs():
    s = assemble(block(BOYD_BRDF_VS, "vertex", BRDF_DECL)).stats
    # m4x4 4 + m4x4 4 + m3x3 3 + m3x3 3 + 21 one-slot instructions = 35
    assert s.total_slots == 35 and s.arithmetic_slots == 35
    assert s.temps_used == 6                       # r0 r1 r2 r4 r5 r6
    # c0–c7 through the matrices, c9, c10, c16
    assert s.constants_used == 11 and s.highest["c"] == 16
    assert s.highest["oT"] == 3


def test_stats_of_ps14_phases_and_dependent_reads():
    prog = assemble(block("ps.1.4\ntexld r0, t0\ntexcrd r1.rgb, t1\nmov r1.a, c0\n"
                          "phase\ntexld r2, r0\ntexld r3, r1_dz\nmul r0.rgb, r2, r3\n"
                          "+add r0.a, r2, v0"))
    assert check(prog) == []
    s = prog.stats
    assert s.phase_slots == {1: (2, 1), 2: (2, 1)}     # co-issued add shares the mul's slot
    assert s.dependent_read_depth == 2
    assert s.samplers_used == {0, 2, 3} and s.texcoords_used == {0, 1}


def test_stats_dependent_depth_and_ps2x_features():
    prog = assemble(block("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\ntexld r1, r0, s0\n"
                          "add r2, r1, t0\ntexld r2, r2, s0\nmov oC0, r2"))
    assert prog.stats.dependent_read_depth == 3
    assert check(prog) == []
    x = assemble(block("ps_2_x\ndcl t0\nsetp_gt p0, t0, c0\n(p0) mov r0, t0.yxwz\n"
                       "dsx r1, t0\nmov oC0, r0"))
    assert check(x) == []
    assert x.stats.uses_predication and x.stats.uses_arbitrary_swizzle and x.stats.uses_gradients


# -- programs of every version that must validate (no false alarms) ----------------------------

VALID = [
    ("ps11 co-issue and def", "ps.1.1\ndef c0, 0.5, 0.5, 0.5, 1.0\ntex t0\ntexcoord t1\n"
     "dp3_sat r0.rgb, t0_bx2, t1_bx2\n+mov r0.a, t0.a\nmul r0, r0, c0"),
    ("ps13 texm3x3vspec", "ps.1.3\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\n"
     "texm3x3vspec t3, t0_bx2\nmov r0, t3"),
    ("ps11 texm3x3spec", "ps.1.1\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\n"
     "texm3x3spec t3, t0_bx2, c0\nmov r0, t3"),
    ("ps11 texbem", "ps.1.1\ntex t0\ntexbem t1, t0\nmov r0, t1"),
    ("ps11 texbeml", "ps.1.1\ntex t0\ntexbeml t1, t0\nmov r0, t1"),
    ("ps12 texreg", "ps.1.2\ntex t0\ntexreg2ar t1, t0\ntexreg2gb t2, t0\ntexdp3tex t3, t0\n"
     "mul r0, t1, t2\nmul r0, r0, t3"),
    ("ps11 cnd and blue selector", "ps.1.1\ntex t0\nmov r0.a, t0.b\nmul r1.rgb, t0, v0\n"
     "+mul r1.a, t0.a, v0.a\ncnd r0, r0.a, r1, v1"),
    ("ps14 two phases", "ps.1.4\ntexld r0, t0.xyz\ntexld r1, t1_dw.xyw\ntexcrd r2.rgb, t2\n"
     "bem r3.rg, r0, r1\nphase\ntexld r3, r3\ncmp r0, r2, r3, r0\ncnd r0.rgb, r1, r0, r3\n"
     "dp3_x2 r0.a, r0, v0"),
    ("ps20 instruction mix", "ps_2_0\ndcl t0\ndcl t1.xyz\ndcl v0\ndcl_2d s0\ndcl_cube s1\n"
     "def c0, 1, 2, 3, 4\ntexldp r0, t0, s0\ntexldb r1, t1, s1\nnrm r2, t1\n"
     "sincos r3.xy, r0.x, c1, c2\ndp2add r4, r0, r1, c0.x\nlrp r5, r0, r1, v0\n"
     "max r5, r5, c0\nmin r5, r5, c0\nabs_pp r6, r5\nfrc r6, r6\ncrs r7.xyz, r2, r1\n"
     "exp r8, r0.x\nlog r8, r8.y\ntexkill t0\nm3x3 r9.xyz, r0, c3\nmul_sat r10, r5, v0.wzyx\n"
     "mov oC0, r10\nmov oDepth, r0.x"),
    ("vs11 instruction mix", "vs.1.1\ndcl_position v0\ndcl_normal v3\nm4x4 oPos, v0, c0\n"
     "expp r0, v0.x\nlogp r1, v0.y\nlit r2, r1\ndst r3, r0, r1\nfrc r4.y, v0\n"
     "sge r5, v0, c4\nslt r5, v0, c5\nmov a0.x, v3.x\nmov oD0, c[a0.x + 10]\nmov oFog, r0.x\n"
     "mov oPts, r1.x\nrcp r6.w, r0.x\nrsq r6, r0\nmax r7, r6, v3\nmin r7, r7, v0\nmov oT7, r7"),
    ("vs20 flow control", "vs_2_0\ndcl_position v0\ndefb b0, true\ndefi i0, 3, 0, 1, 0\n"
     "mova a0.x, v0.x\nm4x4 oPos, v0, c[a0.x]\nrep i0\nadd r0, v0, c1\nendrep\nif b0\n"
     "mov oD0, r0\nelse\nmov oD0, c0\nendif\nloop aL, i0\nadd r1, r0, c[aL]\nendloop\n"
     "sgn r2, r1, r3, r4\ncall l0\nret\nlabel l0\nret"),
    ("ps30", "ps_3_0\ndcl_texcoord0 v0\ndcl_2d s0\ntexld r0, v0, s0\nmov r1, r0_abs\n"
     "add r1, -r1_abs, c0\ntexldl r2, v0, s0\nif_gt r0.x, c0.x\nmov r1, c1\nendif\nmov oC0, r1"),
    ("vs30", "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\nm4x4 o0, v0, c0\n"
     "mov o1, v0"),
]


@pytest.mark.parametrize("name,src", VALID, ids=[v[0] for v in VALID])
def test_valid_programs_of_every_version(name, src):
    assemble_clean(src, "vertex" if src.startswith("vs") else "pixel")


def test_vs11_scalar_and_matrix_semantics_rows():
    prog = assemble(block("vs.1.1\nm3x3 r0.xyz, v0, c4\nrcp r1, v0\nmov oPos, r0", "vertex"))
    m3x3, rcp, _ = prog.instructions
    assert m3x3.info.writes == "xyz" and m3x3.info.slot_cost("vs_1_1") == 3
    assert rcp.info.operands == "dx" and rcp.info.op == "rcp"
    assert "1/a" in rcp.info.formula
