#!/usr/bin/env python3
"""Share of the header code that sits in `detail` namespaces.

Counts lines of code of every header under a directory (default: include/):
blank lines, comments and preprocessor lines are not counted. A line counts as
`detail` when it lies inside a `namespace ... detail {` block (nested blocks
included) or in a file under a `detail/` directory.

    scripts/lib/detail_share.py [DIR] [--files N]
"""
import argparse
import pathlib
import re


def code_lines(text):
    """The lines of `text` with comments and string contents blanked."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    for line in text.split("\n"):
        line = re.sub(r'"([^"\\]|\\.)*"', '""', line)
        yield re.sub(r"//.*", "", line)


def count(path):
    """(code lines, detail lines) of one header."""
    in_detail_directory = "detail" in path.parts[:-1]
    total = detail = 0
    stack = []  # for each open brace: does it open a detail namespace?
    for line in code_lines(path.read_text(encoding="utf-8")):
        opens_detail = re.search(r"namespace\s+(\w+::)*detail\s*\{", line) is not None
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            total += 1
            if in_detail_directory or opens_detail or any(stack):
                detail += 1
        for character in line:
            if character == "{":
                stack.append(opens_detail)
                opens_detail = False
            elif character == "}" and stack:
                stack.pop()
    return total, detail


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory", nargs="?", default="include")
    parser.add_argument("--files", type=int, default=0, help="also list the N files with most detail lines")
    arguments = parser.parse_args()
    counts = {path: count(path) for path in sorted(pathlib.Path(arguments.directory).rglob("*.hpp"))}
    total = sum(t for t, _ in counts.values())
    detail = sum(d for _, d in counts.values())
    print(f"{detail} of {total} lines of header code in detail ({100 * detail / max(total, 1):.1f} %)")
    for path, (_, d) in sorted(counts.items(), key=lambda item: -item[1][1])[: arguments.files]:
        print(f"{d:6d}  {path}")


if __name__ == "__main__":
    main()
