#!/usr/bin/env python3
"""Unity groups for hipair_tests (tests/CMakeLists.txt; docs/performance.md, session 43 build43).

usage: unity_groups.py BATCH FILE...

Prints one line per test unit, "GROUP:FILE", GROUP 0 for a unit compiled on its own. Units in one
group are compiled as one translation unit, so two units that declare the same name at file scope
(their helpers in anonymous namespaces: example(), geneva(), Random, Tally ...) must not share a
group: the names each unit declares at its top level (column 0 under the project's clang-format:
functions, variables, types, aliases) are read here, and a unit joins a group only when it shares
none of them with the units already there. The test is by name, not by signature (conservative).
A unit with a `using namespace` at column 0, a `#define` or the line `// hipair: no unity build`
stays alone (what it changes would reach the units after it). So does a unit that declares, at
file scope, a name the project's headers (include/, src/, kernels/, certify/, tests/unit/*.hpp)
also declare: its own hipair::{anonymous}::Point made `Point` in a header included by a later unit
of its group ambiguous (cspace_radical_ordinate_test.cpp before pin_slot_witness_filter_test.cpp,
session 43), and could silently win an overload a later unit meant for the library's function.

A unit's place is stable: its first choice is a hash of its file name, the next groups are tried
in turn; so adding a unit moves no other unit unless the group it lands in was full.
"""
import hashlib
import os
import re
import sys

TYPE = re.compile(r"^(?:template\s*<.*>\s*)?(?:struct|class|union|enum(?:\s+class|\s+struct)?)\s+(\w+)")
ALIAS = re.compile(r"^(?:template\s*<.*>\s*)?using\s+(\w+)\s*=")
NAMESPACE_ALIAS = re.compile(r"^namespace\s+(\w+)\s*=")
IDENT = re.compile(r"[A-Za-z_]\w*")
KEYWORDS = {"return", "if", "for", "while", "switch", "do", "else", "static_assert", "operator", "extern",
            "friend", "template", "typename", "const", "constexpr", "static", "inline", "auto", "void",
            "int", "long", "unsigned", "double", "bool", "char", "float", "short", "signed", "thread_local",
            "namespace", "using", "case", "default", "new", "delete", "sizeof", "decltype", "noexcept"}


def names_of(path):
    """(names declared at column 0, alone?)"""
    names, alone = set(), False
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith("// hipair: no unity build"):
                alone = True
            if not line or not (line[0].isalpha() or line[0] == "_"):
                if line.startswith("#define"):
                    alone = True
                continue
            line = line.split("//", 1)[0].rstrip()
            if line.startswith("using namespace"):
                alone = True
                continue
            m = TYPE.match(line) or ALIAS.match(line) or NAMESPACE_ALIAS.match(line)
            if m:
                names.add(m.group(1))
                continue
            if line.startswith("namespace") or re.match(r"^template\s*<[^(]*$", line):
                continue
            head = re.split(r"[(={;\[]", line, 1)[0]
            tokens = IDENT.findall(head)
            if not tokens or tokens[0].isupper() or tokens[0] in ("return", "static_assert", "extern"):
                continue  # a macro (TEST, INSTANTIATE_TEST_SUITE_P, ...) or a statement
            candidates = [t for t in tokens if t not in KEYWORDS]
            if candidates:
                names.add(candidates[-1])
    return names, alone


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    batch = int(argv[1])
    files = sorted(argv[2:])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    library = set()
    for folder in ("include", "src", "kernels", "certify", os.path.join("tests", "unit")):
        for base, _, names in os.walk(os.path.join(root, folder)):
            for name in names:
                if name.endswith((".hpp", ".h")):
                    library |= names_of(os.path.join(base, name))[0]
    placed, groupable = {}, []
    for path in files:
        names, alone = names_of(path)
        if alone or batch < 2 or names & library:
            placed[path] = 0
        else:
            groupable.append((path, names))
    count = max(1, -(-len(groupable) * 5 // (4 * batch)))  # a quarter of room: ceil(1.25 n / batch)
    groups = [(set(), []) for _ in range(count)]
    for path, names in groupable:
        first = int(hashlib.sha1(os.path.basename(path).encode()).hexdigest(), 16) % count
        for step in range(count):
            taken, members = groups[(first + step) % count]
            if len(members) < batch and not (taken & names):
                taken |= names
                members.append(path)
                placed[path] = (first + step) % count + 1
                break
        else:
            placed[path] = 0  # no group without a shared name: alone
    for path in files:
        print("%d:%s" % (placed[path], path))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
