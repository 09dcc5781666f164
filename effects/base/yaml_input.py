"""YAML from untrusted files (caps profiles, scenes): safe, bounded, every problem located.

PyYAML's safe loader runs no tags, but on its own it lets `!!int abc` raise a bare ValueError
from the constructor, expands alias bombs (`&a [*b, *b, ...]`) into exponential values, and
reads `1e308` as a string (YAML 1.1 floats need a dot). Here:
- `compose` parses with libyaml where PyYAML has it (its parser bounds nesting itself), then
  walks the node graph once: an alias (a node reached twice) is refused, since neither
  profiles nor scenes need one, and nesting deeper than the `yaml_depth` limit is refused;
- `Constructor` turns a tag that cannot build its value into a located error, bounds integer
  literals (`literal_digits`), and reads exponent-only floats as numbers;
- `Resolver` keeps YAML 1.1's tag for each plain scalar text it has resolved;
- `brief` prints a value for an error message cut to a few dozen characters.
"""
from __future__ import annotations

import re
import reprlib
from typing import Any

import yaml

from effects.base import caches, limits
from effects.base.errors import EffectError, Location

_reprs = reprlib.Repr()
_reprs.maxstring = _reprs.maxother = 60
_reprs.maxlist = _reprs.maxdict = _reprs.maxtuple = _reprs.maxset = 6
_reprs.maxlevel = 3


def brief(value: Any) -> str:
    """`repr(value)` cut short: error messages never print an expanded value."""
    return _reprs.repr(value)


class Constructor(yaml.constructor.SafeConstructor):
    """The safe constructor, whose failures are `ConstructorError`s with the node's mark."""

    def construct_object(self, node: yaml.Node, deep: bool = False) -> Any:
        try:
            return super().construct_object(node, deep)
        except (ValueError, TypeError, OverflowError, ArithmeticError, AttributeError) as exc:
            # AttributeError: `!!timestamp x` (SafeConstructor reads a regex match it did not get)
            value = node.value if isinstance(node, yaml.ScalarNode) else node.tag
            raise yaml.constructor.ConstructorError(
                None, None, f"cannot read {brief(value)} as {node.tag.rsplit(':', 1)[-1]}: "
                f"{brief(str(exc))}", node.start_mark) from None

    def __init__(self) -> None:
        super().__init__()
        self.literal_digits = limits.get("literal_digits")  # read once: a profile has ~20 ints

    def construct_yaml_int(self, node: yaml.ScalarNode) -> int:
        value = str(node.value)
        if len(value) > self.literal_digits:
            raise yaml.constructor.ConstructorError(
                None, None, limits.message("literal_digits", len(value), "an integer"), node.start_mark)
        return super().construct_yaml_int(node)


Constructor.add_constructor("tag:yaml.org,2002:int", Constructor.construct_yaml_int)

class Resolver(yaml.resolver.Resolver):
    """YAML 1.1's resolver, its answer for a plain scalar kept: libyaml's composer asks for
    every scalar, and the 20 bundled profiles repeat the same few hundred names and numbers
    (5,426 asks, 700 texts). The implicit resolvers are the class's, set at import. Only
    short texts are kept, at most 4,096: the memo pins no large value of an untrusted file."""

    def resolve(self, kind: type, value: Any, implicit: Any) -> str:
        if kind is not yaml.ScalarNode or self.yaml_path_resolvers or len(value) > 64:
            return super().resolve(kind, value, implicit)
        key = (type(self), value, implicit)
        tag = _TAGS.get(key)
        if tag is None:
            tag = super().resolve(kind, value, implicit)
            _TAGS.put(key, tag)
        return tag


_TAGS = caches.declare("base.yaml_tags", keys="resolver class, scalar text (64 characters at "
                       "most), implicit flags", entry_bytes=256, max_bytes=4096 * 256)


try:   # PyYAML exports CSafeLoader, not the CParser it is made of
    from yaml.cyaml import CParser as _Parser
except ImportError:  # pragma: no cover - PyYAML built without libyaml
    _Parser = None


if _Parser is not None:
    class Loader(_Parser, Constructor, Resolver):  # type: ignore[misc,valid-type]
        """libyaml's parser and composer, our constructor, YAML 1.1's resolver (+ 1e308)."""

        def __init__(self, stream: str) -> None:
            _Parser.__init__(self, stream)
            Constructor.__init__(self)
            Resolver.__init__(self)
else:  # pragma: no cover - PyYAML without libyaml
    class Loader(yaml.reader.Reader, yaml.scanner.Scanner, yaml.parser.Parser,  # type: ignore[no-redef]
                 yaml.composer.Composer, Constructor, Resolver):
        def __init__(self, stream: str) -> None:
            yaml.reader.Reader.__init__(self, stream)
            yaml.scanner.Scanner.__init__(self)
            yaml.parser.Parser.__init__(self)
            yaml.composer.Composer.__init__(self)
            Constructor.__init__(self)
            Resolver.__init__(self)

# `1e308`, `-2E-3`: numbers, as a reader of a caps table means them (YAML 1.1 wants `1.0e308`).
Loader.add_implicit_resolver("tag:yaml.org,2002:float",
                             re.compile(r"^[-+]?[0-9][0-9_]*[eE][-+]?[0-9]+$"), list("-+0123456789"))


def _where(path: str, mark: Any) -> Location:
    return Location(path, mark.line + 1, mark.column + 1) if mark is not None else Location(path, 1, 1)


def located(exc: yaml.YAMLError, path: str, error: type[EffectError], what: str,
            lines: list[str] | None = None) -> EffectError:
    """A PyYAML error as `error` at its mark, with the source line when `lines` are given."""
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    where = _where(path, mark)
    problem = getattr(exc, "problem", None) or getattr(exc, "context", None) or str(exc)
    line = lines[where.line - 1] if lines and 0 < where.line <= len(lines) else None
    return error(f"{what}: {problem}", where, source_line=line)


def check_tree(root: yaml.Node | None, path: str, error: type[EffectError]) -> None:
    """Refuse aliases and nesting deeper than `yaml_depth`, in one walk over distinct nodes."""
    if root is None:
        return
    depth_limit = limits.get("yaml_depth")
    seen: set[int] = set()
    # depth-first, last child first; a node and its depth on two stacks (no pair per node)
    stack: list[yaml.Node] = [root]
    depths: list[int] = [1]
    while stack:
        node = stack.pop()
        depth = depths.pop()
        if id(node) in seen:
            raise error("YAML aliases (*name) are not accepted here: write the value out",
                        _where(path, node.start_mark))
        seen.add(id(node))
        if isinstance(node, yaml.ScalarNode):
            continue
        if depth > depth_limit:
            raise error(limits.message("yaml_depth", depth, "the YAML nesting"), _where(path, node.start_mark))
        if isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)
        else:
            for pair in node.value:
                stack.extend(pair)
        depths.extend([depth + 1] * (len(stack) - len(depths)))


def compose(text: str, path: str, error: type[EffectError], what: str = "YAML syntax error",
            loader: type = Loader) -> tuple[Any, yaml.Node | None]:
    """Parse `text` into (a loader ready to construct, the checked root node or None)."""
    instance = loader(text)
    try:
        root = instance.get_single_node()
    except yaml.YAMLError as exc:
        instance.dispose()
        raise located(exc, path, error, what, text.splitlines()) from None
    except RecursionError:
        instance.dispose()
        raise error(limits.message("yaml_depth", limits.get("yaml_depth") + 1, "the YAML nesting"),
                    Location(path, 1, 1)) from None
    check_tree(root, path, error)
    return instance, root
