"""Tests of the effect preprocessor: what text lark gets, where each line came from, the errors."""
from __future__ import annotations

import os
import random
import time

import pytest

from effects.base.errors import PreprocessError
from effects.frontend.preprocess import preprocess


def out(text: str, **kwargs) -> str:
    return preprocess(text, **kwargs).text


def error(text: str, **kwargs) -> str:
    with pytest.raises(PreprocessError) as info:
        preprocess(text, **kwargs)
    return str(info.value)


def kept(text: str, **kwargs) -> list[str]:
    """The output lines that are not blank, stripped."""
    return [line.strip() for line in out(text, **kwargs).split("\n") if line.strip()]


def write(folder, name: str, text: str) -> str:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return str(path)


# ------------------------------------------------------------------------------ comments, lines

def test_comments_become_spaces_keeping_lines_and_columns():
    src = "a // line comment\nb /* one */ c\nd /* two\nlines */ e\nf"
    assert out(src) == ("a" + " " * 16 + "\n" + "b" + " " * 11 + "c\n" + "d" + " " * 7 + "\n"
                        + " " * 8 + " e\nf")


def test_comment_markers_inside_string_literals_are_text():
    src = 'string s = "http://x/*y*/"; // gone'
    assert out(src) == 'string s = "http://x/*y*/";' + " " * 8


def test_unterminated_block_comment_is_located_at_its_start():
    assert error("a\n  b /* never closed\nc") == "<string>:2:5: error: unterminated comment"


def test_crlf_and_lone_cr_are_normalised():
    pre = preprocess("a\r\nb\rc\r\n")
    assert pre.text == "a\nb\nc\n"
    assert pre.source_map.lines == [("<string>", 1), ("<string>", 2), ("<string>", 3), ("<string>", 4)]


def test_stray_non_ascii_character_passes_through():
    src = "float f\xe9 = 1; // caf\xe9\nfloat g\x85;"
    assert out(src) == "float f\xe9 = 1;" + " " * 8 + "\nfloat g\x85;"
    # the stored source line is the whole line even with a latin-1 NEL (\x85) in it
    assert preprocess(src).source_map.texts["<string>"][1] == "float g\x85;"


def test_directive_lines_become_empty_lines_and_map_to_themselves():
    pre = preprocess("#define X 1\nX\n#pragma pack\n#line 40\nY")
    assert pre.text == "\n1\n\n\nY"
    assert pre.source_map.lines == [("<string>", n) for n in range(1, 6)]


def test_line_continuation_in_a_directive():
    pre = preprocess("#define SUM(a, b) \\\n    ((a) + \\\n     (b))\nSUM(1, 2)")
    assert pre.text == "\n\n\n((1) + (2))"
    assert pre.source_map.lines[3] == ("<string>", 4)


def test_error_after_multi_line_comment_reports_original_line():
    src = "/* one\ntwo\nthree */\n#error here"
    assert error(src) == "<string>:4:1: error: #error here"


def test_leading_blank_line_and_utf8_bom():
    assert out("\ufeff\ntechnique t {}") == "\ntechnique t {}"


# ------------------------------------------------------------------------------ macros

def test_object_and_function_like_macros():
    src = ("#define ONE 1\n#define ADD(a, b) ((a) + (b))\n"
           "x = ADD(f(1, 2), ONE);")
    assert kept(src) == ["x = ((f(1, 2)) + (1));"]


def test_function_like_macro_name_without_arguments_stays():
    assert kept("#define F(x) [x]\nF + F (2)") == ["F + [2]"]


def test_macro_arguments_may_span_lines_and_keep_the_line_count():
    pre = preprocess("#define F(a, b) a-b\nx F(1,\n  2) y\nz")
    assert pre.text.split("\n") == ["", "x 1-2 y", "", "z"]
    assert pre.source_map.lines[3] == ("<string>", 4)


def test_stringize_and_paste():
    src = ('#define STR(x) #x\n#define CAT(a, b) a##b\n#define REG(n) r##n\n'
           'STR(  a   "q\\n"  b ) CAT(tex, 2D) REG(0).x CAT(, z) CAT(w, )')
    assert kept(src) == ['"a \\"q\\\\n\\" b" tex2D r0.x z w']


def test_undef():
    assert kept("#define X 1\nX\n#undef X\nX") == ["1", "X"]


def test_macro_is_not_expanded_inside_its_own_expansion():
    assert kept("#define A A + 1\nA") == ["A + 1"]
    assert kept("#define A B\n#define B A\nA B") == ["A B"]
    assert kept("#define f(x) x + f(x)\nf(2)") == ["2 + f(2)"]


def test_rescan_picks_up_arguments_that_follow_an_expansion():
    # C 6.10.3.4: the result is rescanned together with the rest of the line
    assert kept("#define CALL F\n#define F(x) <x>\nCALL(3)") == ["<3>"]


def test_no_expansion_inside_string_literals_or_comments():
    assert kept('#define X 9\nX "X" /* X */ // X') == ['9 "X"']


def test_names_inside_numbers_are_not_macros():
    assert kept("#define e5 BAD\n#define X BAD\n1e5 1.X 0x1e5 e5") == ["1e5 1.X 0x1e5 BAD"]


def test_macros_expand_inside_asm_blocks():
    src = ("#define LIGHT_DIR c4\n#define NORMALIZE(r) dp3 r.w, r, r\n"
           "PixelShader ps = asm {\n  ps.1.1\n  NORMALIZE(r0)\n  dp3 r1, r0, LIGHT_DIR ; LIGHT_DIR\n};")
    assert kept(src) == ["PixelShader ps = asm {", "ps.1.1", "dp3 r0.w, r0, r0",
                         "dp3 r1, r0, c4 ; c4", "};"]


def test_defines_given_at_load_act_before_line_one():
    src = "#ifdef pc\nstate = 1;\n#endif\nPixelShader = compile PS_TARGET main();"
    assert kept(src, defines={"PS_TARGET": "ps_2_0", "pc": ""}) == [
        "state = 1;", "PixelShader = compile ps_2_0 main();"]
    assert kept("TWICE(3)", defines={"TWICE(x)": "x x"}) == ["3 3"]
    assert kept("#if FLAG\nyes\n#endif", defines={"FLAG": None}) == ["yes"]


def test_bad_name_in_defines_is_located_in_defines():
    assert error("x", defines={"2X": "1"}) == "<defines>:1:1: error: macro names must be identifiers"


def test_variadic_macro():
    assert kept("#define V(f, ...) f(__VA_ARGS__)\nV(g, 1, (2, 3)) V(h)") == ["g(1, (2, 3)) h()"]


def test_endless_and_exploding_macros_are_located_errors():
    chain = "".join(f"#define A{i} A{i + 1} A{i + 1}\n" for i in range(40)) + "x = A0;"
    start = time.process_time()
    message = error(chain)
    assert time.process_time() - start < 5.0   # the untrusted-input bound (issue 14)
    assert message.startswith("<string>:41:5: error: expansion of macro ")
    assert message.endswith("is too large (more than 300000 tokens)")


# ------------------------------------------------------------------------------ conditionals

def test_if_ifdef_ifndef_elif_else():
    src = ("#define A\n#define B 2\n"
           "#ifdef A\na\n#endif\n#ifndef A\nnot_a\n#endif\n#ifdef Q\nq\n#else\nnot_q\n#endif\n"
           "#if B == 1\none\n#elif B == 2\ntwo\n#elif B == 2\ntwo_again\n#else\nother\n#endif\n"
           "#if defined(A) && defined B && !defined(Q)\ndef\n#endif")
    assert kept(src) == ["a", "not_q", "two", "def"]


def test_skipped_groups_are_not_evaluated():
    src = "#if 0\n#if 1/0\n#bogus\n#error no\n#endif\n#elif 1\nyes\n#elif 1/0\n#endif"
    assert kept(src) == ["yes"]


def test_nested_conditionals():
    src = "#if 1\n#if 0\nno\n#else\nyes\n#endif\n#else\n#if 1\nno2\n#endif\n#endif"
    assert kept(src) == ["yes"]


@pytest.mark.parametrize("expression, value", [
    ("1 + 2 * 3", 7),
    ("(1 + 2) * 3", 9),
    ("10 - 4 - 3", 3),          # left to right
    ("7 / 2", 3),
    ("-7 / 2", -3),             # C truncates toward zero
    ("-7 % 3", -1),
    ("7 % -3", 1),
    ("1 << 4 >> 2", 4),
    ("0x1F", 31),
    ("0X10 + 010", 24),         # hex 16, octal 8
    ("10u + 5UL + 3ll", 18),
    ("~0", -1),
    ("!5", 0),
    ("!!5", 1),
    ("- -3", 3),
    ("+4", 4),
    ("5 & 3", 1),
    ("5 | 3", 7),
    ("5 ^ 3", 6),
    ("1 | 2 ^ 3 & 4", 3),       # & before ^ before |: 3 & 4 = 0, 2 ^ 0 = 2, 1 | 2 = 3
    ("3 == 3", 1),
    ("3 != 3", 0),
    ("2 < 3", 1),
    ("3 <= 2", 0),
    ("3 > 2", 1),
    ("2 >= 3", 0),
    ("1 < 2 == 1", 1),          # relational before equality
    ("1 + 1 << 1", 4),          # + before <<
    ("0 || 2", 1),
    ("2 && 0", 0),
    ("1 || 0 && 0", 1),         # && before ||
    ("0 ? 10 : 20", 20),
    ("1 ? 2 ? 3 : 4 : 5", 3),
    ("UNDEFINED_NAME + 1", 1),  # an undefined identifier is 0
    ("0 && 1 / 0", 0),          # not evaluated
    ("1 || 1 / 0", 1),
    ("1 ? 2 : 1 / 0", 2),
])
def test_if_arithmetic(expression, value):
    assert kept(f"#if ({expression}) == ({value})\nok\n#else\nwrong\n#endif") == ["ok"]


def test_if_sees_macros_but_not_the_operand_of_defined():
    src = "#define LEVEL 2\n#define X Y\n#if LEVEL * 2 == 4 && defined X && !defined Y\nok\n#endif"
    assert kept(src) == ["ok"]


def test_if_values_wrap_to_64_bits():
    assert kept("#if 0x7FFFFFFFFFFFFFFF + 1 < 0\nwrapped\n#endif") == ["wrapped"]


# ------------------------------------------------------------------------------ directive errors

@pytest.mark.parametrize("src, message", [
    ("#if 1 / 0\n#endif", "<string>:1:7: error: division by zero in #if expression"),
    ("#if 2 % (1 - 1)\n#endif", "<string>:1:7: error: division by zero in #if expression"),
    ("x\n#if (1 + 2\n#endif", "<string>:2:11: error: expected ')' in #if expression"),
    ("#if 1 +\n#endif", "<string>:1:8: error: unexpected end of #if expression"),
    ("#if 1 2\n#endif", "<string>:1:7: error: unexpected '2' in #if expression"),
    ("#if\n#endif", "<string>:1:4: error: #if with no expression"),
    ("#if 1.5\n#endif", "<string>:1:5: error: invalid integer constant '1.5' in #if expression"),
    ("#if \"s\"\n#endif", "<string>:1:5: error: unexpected '\"s\"' in #if expression"),
    ("#if defined(\n#endif", "<string>:1:13: error: 'defined' expects a macro name"),
    ("#if 1 << -1\n#endif", "<string>:1:7: error: negative shift count in #if expression"),
    ("#if 0\n#elif 1 / 0\n#endif", "<string>:2:9: error: division by zero in #elif expression"),
    ("#if 1\nx", "<string>:1:1: error: unterminated #if"),
    ("#ifdef A\n#if 1\n#endif", "<string>:1:1: error: unterminated #ifdef"),
    ("a\n  #else", "<string>:2:3: error: #else without #if"),
    ("#endif", "<string>:1:1: error: #endif without #if"),
    ("#elif 1", "<string>:1:1: error: #elif without #if"),
    ("#if 1\n#else\n#else\n#endif", "<string>:3:1: error: #else after #else"),
    ("#if 1\n#else\n#elif 1\n#endif", "<string>:3:1: error: #elif after #else"),
    ("#ifdef\n#endif", "<string>:1:7: error: #ifdef expects a macro name"),
    ("#undef 3", "<string>:1:8: error: #undef expects a macro name"),
    ("#define", "<string>:1:8: error: macro name missing"),
    ("#define 3 x", "<string>:1:9: error: macro names must be identifiers"),
    ("#define defined 1", "<string>:1:9: error: 'defined' cannot be used as a macro name"),
    ("#define F(a, 1) a", "<string>:1:10: error: malformed parameter list for macro 'F'"),
    ("#define F(a, b", "<string>:1:10: error: malformed parameter list for macro 'F'"),
    ("#define F(a, a) a", "<string>:1:10: error: duplicate macro parameter 'a'"),
    ("#define F(a) #b", "<string>:1:14: error: '#' is not followed by a macro parameter"),
    ("#define F(a) ## a", "<string>:1:14: error: '##' cannot appear at either end of a macro expansion"),
    ("#define F(a, b) a\nx = F(1);", "<string>:2:5: error: macro 'F' expects 2 arguments, got 1"),
    ("#define F(a) a\nx = F(1, 2);", "<string>:2:5: error: macro 'F' expects 1 argument, got 2"),
    ("#define F(a) a\n\n  F(1,\n 2\n#endif", "<string>:3:3: error: unterminated argument list invoking macro 'F'"),
    ("#define F(a) a\nF(", "<string>:2:1: error: unterminated argument list invoking macro 'F'"),
    ("#error Shader model 2 required", "<string>:1:1: error: #error Shader model 2 required"),
    ("  #  error", "<string>:1:3: error: #error"),
    ("#warning x", "<string>:1:1: error: unknown preprocessor directive '#warning'"),
    ("x\n#!junk here", "<string>:2:1: error: unknown preprocessor directive '#!junk'"),
    ("#include", "<string>:1:1: error: #include expects \"FILENAME\" or <FILENAME>"),
    ("#include common.fx", "<string>:1:10: error: #include expects \"FILENAME\" or <FILENAME>"),
    ("#include \"x.fx", "<string>:1:10: error: #include expects \"FILENAME\" or <FILENAME>"),
    ("#include \"\"", "<string>:1:10: error: empty file name in #include"),
])
def test_malformed_directives(src, message):
    assert error(src) == message


def test_error_carries_the_source_line_for_the_caret():
    with pytest.raises(PreprocessError) as info:
        preprocess("ok\n#if 1 / 0\n#endif", "fx/a.fx")
    assert info.value.report() == "fx/a.fx:2:7: error: division by zero in #if expression\n#if 1 / 0\n      ^"


def test_null_directive_and_pragma_are_ignored():
    assert out("#\n#pragma warning(disable: 1234)\nx") == "\n\nx"


# ------------------------------------------------------------------------------ includes

def test_include_splices_file_and_maps_lines_into_it(tmp_path):
    write(tmp_path, "lib/common.fx", "float a;\n#define K 4\nfloat b = K;\n")
    main = write(tmp_path, "main.fx", "// main\n#include \"lib/common.fx\"\nfloat c = K;\n")
    pre = preprocess(open(main).read(), main)
    common = os.path.join(str(tmp_path), "lib", "common.fx")
    assert pre.text.split("\n") == ["       ", "float a;", "", "float b = 4;", "float c = 4;", ""]
    assert pre.source_map.lines == [(main, 1), (common, 1), (common, 2), (common, 3), (main, 3), (main, 4)]
    assert pre.files == (main, common)
    assert pre.source_map.source_line(pre.source_map.locate(4, 1)) == "float b = K;"


def test_error_in_included_file_reports_that_file_and_line(tmp_path):
    inc = write(tmp_path, "inc.fx", "/* two\nlines */\n#if 1\n#error from include\n#endif\n")
    main = write(tmp_path, "main.fx", "a\n#include \"inc.fx\"\n")
    assert error(open(main).read(), path=main) == f"{inc}:4:1: error: #error from include"


def test_quoted_include_searches_own_folder_first_then_include_dirs(tmp_path):
    write(tmp_path, "fx/x.fx", "from_fx_folder")
    write(tmp_path, "dir1/x.fx", "from_dir1")
    write(tmp_path, "dir1/only1.fx", "only_in_dir1")
    write(tmp_path, "dir2/only1.fx", "also_in_dir2")
    main = str(tmp_path / "fx" / "main.fx")
    dirs = [str(tmp_path / "dir1"), str(tmp_path / "dir2")]
    assert kept('#include "x.fx"\n#include "only1.fx"', path=main, include_dirs=dirs) == [
        "from_fx_folder", "only_in_dir1"]


def test_angle_include_searches_include_dirs_first(tmp_path):
    write(tmp_path, "fx/x.fx", "from_fx_folder")
    write(tmp_path, "dir1/x.fx", "from_dir1")
    write(tmp_path, "fx/y.fx", "y_from_fx_folder")
    main = str(tmp_path / "fx" / "main.fx")
    assert kept("#include <x.fx>\n#include <y.fx>", path=main, include_dirs=[str(tmp_path / "dir1")]) == [
        "from_dir1", "y_from_fx_folder"]


def test_backslash_include_path(tmp_path):
    write(tmp_path, "include/common.fx", "common")
    main = str(tmp_path / "fx" / "main.fx")
    assert kept('#include "..\\include\\common.fx"', path=main) == ["common"]


def test_text_includes_from_current_directory(tmp_path, monkeypatch):
    write(tmp_path, "here.fx", "from_cwd")
    monkeypatch.chdir(tmp_path)
    pre = preprocess('#include "here.fx"')
    assert pre.text == "from_cwd"
    assert pre.files == ("<string>", "here.fx")


def test_include_macro_name(tmp_path):
    write(tmp_path, "a.fx", "from_a")
    assert kept('#define FILE "a.fx"\n#include FILE', path=str(tmp_path / "m.fx")) == ["from_a"]


def test_include_handler_maps_names_and_can_defer(tmp_path):
    lib = write(tmp_path, "engine/lib.fx", "from_lib")
    write(tmp_path, "local.fx", "from_local")
    asked = []

    def handler(name: str, including: str):
        asked.append((name, including))
        return lib if name.startswith("shaders:") else None

    main = str(tmp_path / "main.fx")
    assert kept('#include "shaders:../lib/lib.fx"\n#include "local.fx"', path=main,
                include_handler=handler) == ["from_lib", "from_local"]
    assert asked == [("shaders:../lib/lib.fx", main), ("local.fx", main)]


def test_missing_include_is_located_at_the_name(tmp_path):
    main = str(tmp_path / "main.fx")
    message = error('x\n  #include "nope.fx"', path=main, include_dirs=["/inc"])
    assert message == (f"{main}:2:12: error: cannot open include file 'nope.fx' "
                       f"(searched: {tmp_path}, /inc)")


def test_missing_file_from_include_handler(tmp_path):
    main = str(tmp_path / "main.fx")
    message = error('#include "shaders:x"', path=main, include_handler=lambda n, p: "/no/such.fx")
    assert message == f"{main}:1:10: error: cannot open include file 'shaders:x' (the include handler gave '/no/such.fx')"


def test_include_cycle_names_the_chain(tmp_path):
    a = write(tmp_path, "a.fx", '#include "b.fx"\n')
    b = write(tmp_path, "b.fx", 'x\n#include "a.fx"\n')
    assert error(open(a).read(), path=a) == f"{b}:2:10: error: #include cycle: {a} -> {b} -> {a}"


def test_pragma_once_includes_a_file_once(tmp_path):
    write(tmp_path, "once.fx", "#pragma once\nbody\n")
    main = str(tmp_path / "main.fx")
    assert kept('#include "once.fx"\n#include "once.fx"', path=main) == ["body"]


def test_include_guard_allows_the_same_file_twice(tmp_path):
    write(tmp_path, "g.fx", "#ifndef G_FX\n#define G_FX\nbody\n#endif\n")
    main = str(tmp_path / "main.fx")
    assert kept('#include "g.fx"\n#include "g.fx"', path=main) == ["body"]


def test_include_root_rejects_escapes(tmp_path):
    write(tmp_path, "secret.txt", "secret")
    write(tmp_path, "root/inc/ok.fx", "ok")
    main = str(tmp_path / "root" / "fx" / "main.fx")
    root = str(tmp_path / "root")
    assert kept('#include "../inc/ok.fx"', path=main, include_root=root) == ["ok"]
    message = error('#include "..\\..\\secret.txt"', path=main, include_root=root)
    assert message == f"{main}:1:10: error: include '..\\..\\secret.txt' escapes the include root '{root}'"


def test_include_root_sees_through_symlinks(tmp_path):
    write(tmp_path, "outside.fx", "outside")
    (tmp_path / "root").mkdir()
    os.symlink(tmp_path / "outside.fx", tmp_path / "root" / "link.fx")
    main = str(tmp_path / "root" / "main.fx")
    message = error('#include "link.fx"', path=main, include_root=str(tmp_path / "root"))
    assert "escapes the include root" in message


def test_include_depth_is_limited(tmp_path):
    for i in range(70):
        write(tmp_path, f"f{i}.fx", f'#include "f{i + 1}.fx"\n')
    write(tmp_path, "f70.fx", "end\n")
    path = str(tmp_path / "f0.fx")
    message = error(open(path).read(), path=path)
    # f0 is the effect; f0 -> f1 -> ... -> f64 is 64 levels, f64's own #include is one too many
    assert message == f"{tmp_path}/f64.fx:1:10: error: #include nested too deeply (more than 64 levels)"


def test_include_of_empty_file_keeps_a_line(tmp_path):
    empty = write(tmp_path, "empty.fx", "")
    main = str(tmp_path / "main.fx")
    pre = preprocess('a\n#include "empty.fx"\nb', main)
    assert pre.text == "a\n\nb"
    assert pre.source_map.lines == [(main, 1), (empty, 1), (main, 3)]


# ------------------------------------------------------------------------------ robustness, speed

def _result_or_error(text: str, **kwargs) -> float:
    # CPU time of this process: the bound is on the work done, not on how busy the machine is
    start = time.process_time()
    try:
        preprocess(text, **kwargs)
    except PreprocessError as exc:
        assert exc.line >= 1 and exc.column >= 1
    return time.process_time() - start


def _junk() -> str:
    rng = random.Random(7)
    return bytes(rng.randrange(256) for _ in range(2_000_000)).decode("latin-1")


PATHOLOGICAL = {
    "junk": _junk,
    "junk_without_directives": lambda: _junk().replace("#", "x").replace("/*", "/ "),
    "nested_if": lambda: "#if 1\n" * 10_000 + "x\n" + "#endif\n" * 10_000,
    "long_line": lambda: "a " * 500_000,
    "long_line_macros": lambda: "#define a b c\n" + "a " * 500_000,
    "deep_parens": lambda: "#if " + "(" * 150_000 + "1\n#endif",
    "deep_macro_calls": lambda: "#define F(x) x\n" + "F(" * 50_000 + ")" * 50_000,
    "unterminated_call": lambda: "#define F(x) x\nF(" + "\na" * 100_000,
    "long_directive": lambda: "#define A " + "x " * 500_000,
    "exponential": lambda: "".join(f"#define A{i} A{i + 1} A{i + 1}\n" for i in range(60)) + "A0",
}


@pytest.mark.parametrize("name", sorted(PATHOLOGICAL))
def test_pathological_input_is_quick(name):
    assert _result_or_error(PATHOLOGICAL[name]()) < 2.0
    assert _result_or_error(PATHOLOGICAL[name](), defines={"a": "b", "F(x)": "x x"}) < 2.0


def test_ten_thousand_nested_ifs_give_the_right_text():
    pre = preprocess("#if 1\n" * 10_000 + "x\n" + "#endif\n" * 10_000)
    assert pre.text.strip() == "x"


def test_deep_expression_nesting_is_a_located_error():
    assert error("#if " + "(" * 100 + "1" + ")" * 100 + "\n#endif") == (
        "<string>:1:69: error: #if expression nests too deeply")

