#!/usr/bin/env python3
"""Every public free function of core/ is named by some test (STYLE: "every public function of
core/ has a test").

Scans the namespace-scope function declarations of core/**/*.hpp (not the class members, not
namespace detail, not the *_internal.hpp / identify_loop.hpp headers, which are private to their
folder) and fails, listing them, when a declared name occurs in no file under tests/. A name
that occurs is not proof of a good test, only the floor: the review checks what the test
asserts.

Usage: public_functions_tested.py SOURCE_DIR
"""
import pathlib
import re
import sys

PRIVATE = re.compile(r"(_internal\.hpp|identify_loop\.hpp)$")
DECL = re.compile(
    r"(?:^|[;}])\s*(?:template\s*<[^>]*>\s*)?(?:inline\s+|constexpr\s+|static\s+)*"
    r"[\w:<>,&*\s]+?[\s*&]([a-z]\w*)\s*\([^;{}]*\)\s*(?:const\s*)?(?:noexcept\s*)?(?=;)",
    re.S,
)


def namespace_scope_text(text: str) -> str:
    """The header without comments, without the bodies of classes, structs and functions, and
    without namespace detail (implementation details that a header must show, e.g. templates)."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    out, stack = [], []
    pieces = re.split(r"([{}])", text)
    for i, piece in enumerate(pieces):
        if piece == "{":
            before = pieces[i - 1] if i else ""
            ns = re.search(r"namespace\s*([\w:]*)\s*$", before)
            stack.append("body" if not ns or ns.group(1).split("::")[-1] == "detail" else "ns")
            out.append(";")
        elif piece == "}":
            if stack:
                stack.pop()
            out.append(";")
        elif "body" not in stack:
            out.append(piece)
    return "".join(out)


def declared_functions(core: pathlib.Path):
    for header in sorted(core.rglob("*.hpp")):
        if PRIVATE.search(header.name):
            continue
        scope = namespace_scope_text(header.read_text(encoding="utf-8", errors="replace"))
        for m in DECL.finditer(scope):
            if m.group(1) not in {"operator", "static_assert"}:
                yield header, m.group(1)


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    me = pathlib.Path(__file__).resolve()
    tests = "\n".join(p.read_text(encoding="utf-8", errors="replace")
                      for p in (root / "tests").rglob("*") if p.is_file() and p.resolve() != me
                      and p.suffix in {".cpp", ".hpp", ".py", ".sh"})
    found = list(declared_functions(root / "core"))
    missing = sorted({(h.relative_to(root).as_posix(), n) for h, n in found
                      if not re.search(r"\b" + re.escape(n) + r"\b", tests)})
    print(f"{len({n for _, n in found})} public free functions declared in core/ headers; "
          f"{len(missing)} named by no test")
    for header, name in missing:
        print(f"  {header}: {name}")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
