#!/usr/bin/env python3
"""Functions longer than a limit in the library and cli/ (tests and benchmarks aside), by a brace
scan that skips comments and strings. Usage: long_functions.py [LIMIT]; exit 1 naming each."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ["common", "images", "scene", "basis", "volume", "bake", "formats", "validate", "cli"]
DEFINITION = re.compile(r"\)\s*(const|override|noexcept|final|\s)*(->\s*[\w:<>,\s*&]+)?\s*(:[^{};]*)?$")
TYPE = re.compile(r"\b(namespace|struct|class|enum|union)\b[^;{}()]*$")


def without_comments_and_strings(text):
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif text.startswith("/*", i):
            end = text.find("*/", i) + 2
            out.append("\n" * text[i:end].count("\n"))
            i = end
        elif text[i] == '"' and i > 0 and text[i - 1] == "R":
            delimiter = re.match(r'"([^(]*)\(', text[i:]).group(1)
            end = text.find(")" + delimiter + '"', i) + len(delimiter) + 2
            out.append('""' + "\n" * text[i:end].count("\n"))
            i = end
        elif text[i] in "\"'":
            j = i + 1
            while j < n and text[j] != text[i]:
                j += 2 if text[j] == "\\" else 1
            out.append('""')
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def long_functions(path, limit):
    lines = without_comments_and_strings(path.read_text()).split("\n")
    stack = []  # (kind, first line) of each open brace
    for number, line in enumerate(lines, 1):
        for brace in re.finditer(r"[{}]", line):
            if brace.group() == "{":
                before = (" ".join(lines[max(0, number - 4):number - 1]) + " " + line[:brace.start()]).strip()
                at_scope = all(kind == "scope" for kind, _ in stack)
                if at_scope and DEFINITION.search(before) and not TYPE.search(before) and not before.endswith("="):
                    kind = "function"
                elif at_scope and TYPE.search(before):
                    kind = "scope"
                else:
                    kind = "inner"
                stack.append((kind, number))
            elif stack:
                kind, first = stack.pop()
                if kind == "function" and number - first + 1 > limit:
                    yield first, number - first + 1


limit = int(sys.argv[1]) if len(sys.argv) > 1 else 80
found = [f"{path.relative_to(ROOT)}:{first}: {length} lines"
         for folder in FOLDERS for path in sorted((ROOT / folder).glob("*.[ch]*")) if path.suffix in (".h", ".cpp")
         for first, length in long_functions(path, limit)]
print("\n".join(found) if found else f"no function outside tests and bench is longer than {limit} lines")
sys.exit(1 if found else 0)
