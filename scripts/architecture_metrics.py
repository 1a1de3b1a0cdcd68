#!/usr/bin/env python3
"""Architecture figures of the workspace, deterministic (sorted, no timestamps).

Standard library only. Usage: scripts/architecture_metrics.py [--list] (run from the workspace root).

Prints:
  1. floors: the layer order the library's import graph implies (strongly connected components
     collapsed, floor = 1 + highest floor imported), the cycles among top-level modules, and the
     number of floors of the declared table crates/ehl-bearing/layers.txt;
  2. imports running back up: per (module -> module) pair of top-level modules of
     crates/ehl-bearing/src, the `use crate::x` / `crate::x::` paths where x is on the same or a
     higher floor of the declared table (the check of crates/ehl-bearing/tests/layers.rs);
  3. functions over 120 lines (from the `fn` line to its closing brace) per crate, library code
     (src/ outside #[cfg(test)] modules) and test code (tests/, #[cfg(test)] modules) apart;
  4. serde_json::Value uses per crate outside a report layer (src/*/report*): mentions of the type
     `Value` (imported from serde_json or spelled serde_json::Value), `Map`, and `json!` calls;
  5. string-built errors in library code: the error variants with a String payload (tuple
     variants `V(String)`) and the places that build them;
  6. `#[allow(clippy::too_many_arguments)]` allowances per crate.
With --list the individual items are printed under each count.

Imports are counted in code only: comments and string literals are blanked first, and
#[cfg(test)] modules are left out of the import graph.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIB = os.path.join(ROOT, "crates", "ehl-bearing")
LIB_SRC = os.path.join(LIB, "src")
LONG = 120
LIST = "--list" in sys.argv


def rs_files(d):
    out = []
    for base, dirs, files in os.walk(d):
        dirs.sort()
        for f in sorted(files):
            if f.endswith(".rs"):
                out.append(os.path.join(base, f))
    return sorted(out)


def blank(text):
    """The text with comments and the contents of string and char literals replaced by spaces
    (newlines kept), so that offsets and line numbers stay those of the original."""
    out = list(text)
    n = len(text)
    i = 0

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            wipe(i, j)
            i = j
        elif (c == "r" or text.startswith("br", i)) and re.match(r'b?r#*"', text[i:]) and (
            i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
        ):
            m = re.match(r'b?r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            wipe(i + m.end(), j - len(end))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            wipe(i + 1, j)
            i = j + 1
        elif c == "'":
            if i + 1 < n and text[i + 1] == "\\":
                j = text.find("'", i + 2)
                wipe(i + 1, j)
                i = j + 1
            elif i + 2 < n and text[i + 2] == "'":
                wipe(i + 1, i + 2)
                i = i + 3
            else:
                i += 1  # a lifetime
        else:
            i += 1
    return "".join(out)


def match_brace(code, open_at):
    depth = 0
    for k in range(open_at, len(code)):
        if code[k] == "{":
            depth += 1
        elif code[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(code) - 1


def test_spans(code):
    """(start, end) offsets of #[cfg(test)] modules."""
    spans = []
    for m in re.finditer(r"#\[cfg\(test\)\]\s*(pub(\([^)]*\))?\s+)?mod\s+\w+\s*\{", code):
        spans.append((m.start(), match_brace(code, m.end() - 1)))
    return spans


def inside(spans, pos):
    return any(a <= pos <= b for a, b in spans)


def line_of(code, pos):
    return code.count("\n", 0, pos) + 1


def module_of(path):
    rel = os.path.relpath(path, LIB_SRC).split(os.sep)
    return rel[0][:-3] if rel[0].endswith(".rs") else rel[0]


# Re-exports at the crate root, and the module that owns them.
ROOT_ITEMS = {"Error": "error", "Result": "error", "ContactLaw": "contact_law", "HertzLaw": "contact_law"}


def read_layers():
    floors, anyw = {}, set()
    for raw in open(os.path.join(LIB, "layers.txt")):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        key, mods = line.split(":", 1)
        if key.strip() == "any":
            anyw.update(mods.split())
        else:
            for m in mods.split():
                floors[m] = int(key)
    return floors, anyw


def import_graph():
    """{(from, to): [(file, line, text)]} over top-level modules of the library."""
    edges = {}
    for path in rs_files(LIB_SRC):
        src = module_of(path)
        if src == "lib":
            continue
        text = open(path, encoding="utf-8").read()
        code = blank(text)
        spans = test_spans(code)
        for m in re.finditer(r"\bcrate::(\w+)", code):
            if inside(spans, m.start()):
                continue
            name = m.group(1)
            dst = ROOT_ITEMS.get(name, name)
            if dst == src:
                continue
            ln = line_of(code, m.start())
            rel = os.path.relpath(path, ROOT)
            edges.setdefault((src, dst), []).append((rel, ln, text.splitlines()[ln - 1].strip()))
    return edges


def implied_floors(edges, mods):
    adj = {m: sorted({b for (a, b) in edges if a == m and b in mods}) for m in mods}
    # Tarjan's strongly connected components
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in adj[v]:
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(mods):
        if v not in index:
            strong(v)
    comp_of = {m: i for i, c in enumerate(comps) for m in c}
    floor = {}

    def fl(ci):
        if ci not in floor:
            deps = {comp_of[w] for m in comps[ci] for w in adj[m]} - {ci}
            floor[ci] = 1 + max((fl(d) for d in deps), default=0)
        return floor[ci]

    for ci in range(len(comps)):
        fl(ci)
    return comps, {m: floor[comp_of[m]] for m in mods}


def functions(path):
    """[(name, first line, lines, in test code)] of the functions with a body."""
    text = open(path, encoding="utf-8").read()
    code = blank(text)
    spans = test_spans(code)
    is_test_file = (
        os.sep + "tests" + os.sep in path
        or os.sep + "benches" + os.sep in path
        or os.path.basename(path) == "tests.rs"
    )
    out = []
    for m in re.finditer(r"\bfn\s+(\w+)", code):
        j = m.end()
        depth = 0
        while j < len(code):
            ch = code[j]
            if ch in "([":
                depth += 1
            elif ch in ")]":
                depth -= 1
            elif depth == 0 and ch in "{;":
                break
            j += 1
        if j >= len(code) or code[j] == ";":
            continue
        end = match_brace(code, j)
        a, b = line_of(code, m.start()), line_of(code, end)
        out.append((m.group(1), a, b - a + 1, is_test_file or inside(spans, m.start())))
    return out


def crates():
    d = os.path.join(ROOT, "crates")
    return sorted(c for c in os.listdir(d) if os.path.isfile(os.path.join(d, c, "Cargo.toml")))


def crate_files(crate):
    base = os.path.join(ROOT, "crates", crate)
    files = []
    for sub in ("src", "tests", "benches", "examples"):
        files += rs_files(os.path.join(base, sub))
    return files


def value_uses(path):
    text = open(path, encoding="utf-8").read()
    code = blank(text)
    spans = test_spans(code)
    imports_value = re.search(r"use\s+serde_json::(\{[^}]*\bValue\b[^}]*\}|Value\b)", code)
    imports_map = re.search(r"use\s+serde_json::(\{[^}]*\bMap\b[^}]*\}|Map\b)", code)
    hits = []
    for m in re.finditer(r"\b(serde_json::Value|serde_json::Map|serde_json::json!|json!|Value|Map)\b", code):
        tok = m.group(1)
        if inside(spans, m.start()):
            continue
        if tok == "Value" and not imports_value:
            continue
        if tok == "Map" and not imports_map:
            continue
        before = code[max(0, m.start() - 12) : m.start()]
        if tok in ("Value", "Map") and before.rstrip().endswith("::"):
            continue  # serde_json::Value counted once, not twice
        if tok in ("Value", "Map") and re.search(r"use\s+serde_json::\{?[^;]*$", code[max(0, m.start() - 80) : m.start()]):
            continue  # the import itself
        hits.append((line_of(code, m.start()), tok))
    # json! written as `json!(`: \b before ! does not match, so find them separately
    for m in re.finditer(r"\b(?:serde_json::)?json!\s*[\(\[\{]", code):
        if not inside(spans, m.start()):
            hits.append((line_of(code, m.start()), "json!"))
    return sorted(set(hits))


def string_errors():
    """The String-payload tuple variants of the library's error enums, and where they are built."""
    variants = []
    sites = []
    files = rs_files(LIB_SRC)
    texts = {p: open(p, encoding="utf-8").read() for p in files}
    codes = {p: blank(t) for p, t in texts.items()}
    for p, code in codes.items():
        for m in re.finditer(r"pub\s+enum\s+(\w*Error)\b[^{]*\{", code):
            end = match_brace(code, m.end() - 1)
            body = code[m.end() : end]
            for v in re.finditer(r"\b([A-Z]\w*)\s*\(\s*String\s*\)", body):
                variants.append((m.group(1), v.group(1), os.path.relpath(p, ROOT)))
    variants.sort()
    names = {(e, v) for e, v, _ in variants}
    for p, code in codes.items():
        spans = test_spans(code)
        text = texts[p]
        for m in re.finditer(r"\b(\w*Error)::([A-Z]\w*)\s*\(", code):
            if (m.group(1), m.group(2)) not in names or inside(spans, m.start()):
                continue
            close = m.end()
            depth = 1
            while close < len(code) and depth:
                depth += {"(": 1, ")": -1}.get(code[close], 0)
                close += 1
            arg = text[m.end() : close - 1]
            after = code[close : close + 12].lstrip(") \n")
            if after.startswith("=>") or after.startswith("|"):
                continue  # a match pattern
            if re.fullmatch(r"\s*(ref\s+)?[a-z_]\w*\s*", arg) and re.search(r"\b(if\s+let|let)\s*$", code[max(0, m.start() - 20) : m.start()]):
                continue  # a let pattern
            ln = line_of(code, m.start())
            sites.append((os.path.relpath(p, ROOT), ln, f"{m.group(1)}::{m.group(2)}", text.splitlines()[ln - 1].strip()))
    return variants, sorted(sites)


def main():
    floors, anyw = read_layers()
    edges = import_graph()
    mods = sorted({module_of(p) for p in rs_files(LIB_SRC)} - {"lib"})
    # the cross-cutting modules (the crate Error) left out: they would join every module in one cycle
    comps, implied = implied_floors(edges, [m for m in mods if m not in anyw])

    print("# Architecture metrics (scripts/architecture_metrics.py)")
    print()
    print("## 1. Floors of crates/ehl-bearing/src")
    print(f"implied by the import graph (without {', '.join(sorted(anyw))}): {max(implied.values())} floors")
    for f in sorted(set(implied.values())):
        print(f"  {f:2d}: " + " ".join(sorted(m for m in implied if implied[m] == f)))
    cycles = [c for c in comps if len(c) > 1]
    print(f"import cycles (strongly connected groups of modules): {len(cycles)}")
    for c in cycles:
        print("  " + " ".join(c))
    print(f"declared (crates/ehl-bearing/layers.txt): {len(set(floors.values()))} floors")
    missing = [m for m in mods if m not in floors and m not in anyw]
    if missing:
        print("  modules not in the table: " + " ".join(missing))
    print()

    print("## 2. Imports running back up (against the declared floors)")
    back = []
    for (a, b), uses in sorted(edges.items()):
        if a in anyw or b in anyw or a not in floors or b not in floors:
            continue
        if floors[b] >= floors[a]:
            back.append((a, b, uses))
    print(f"module pairs: {len(back)}; paths: {sum(len(u) for _, _, u in back)}")
    for a, b, uses in back:
        print(f"  {a} (floor {floors[a]}) -> {b} (floor {floors[b]}): {len(uses)}")
        if LIST:
            for f, ln, t in uses:
                print(f"      {f}:{ln}: {t}")
    print()

    print(f"## 3. Functions over {LONG} lines")
    total_lib = total_test = 0
    rows = []
    for c in crates():
        lib_n = test_n = 0
        for p in crate_files(c):
            for name, ln, n, is_test in functions(p):
                if n > LONG:
                    if is_test:
                        test_n += 1
                    else:
                        lib_n += 1
                    rows.append((c, is_test, os.path.relpath(p, ROOT), ln, name, n))
        total_lib += lib_n
        total_test += test_n
        print(f"  {c}: {lib_n} in library code, {test_n} in tests")
    print(f"  total: {total_lib} in library code, {total_test} in tests")
    if LIST:
        for c, is_test, p, ln, name, n in sorted(rows, key=lambda r: (r[0], r[1], -r[5], r[2], r[3])):
            print(f"      {'test ' if is_test else ''}{p}:{ln} {name} ({n} lines)")
    print()

    print("## 4. serde_json::Value uses outside a report layer (code outside tests)")
    total = 0
    per = []
    for c in crates():
        n = 0
        for p in rs_files(os.path.join(ROOT, "crates", c, "src")):
            rel = os.path.relpath(p, ROOT)
            if re.search(r"/src/report(s)?(/|\.rs$)", rel):
                continue
            hits = value_uses(p)
            if hits:
                per.append((rel, hits))
                n += len(hits)
        total += n
        print(f"  {c}: {n}")
    print(f"  total: {total} in {len(per)} files")
    if LIST:
        for rel, hits in per:
            print(f"      {rel}: {len(hits)}")
    print()

    print("## 5. String-built errors in library code (crates/ehl-bearing/src, outside tests)")
    variants, sites = string_errors()
    print(f"String-payload error variants: {len(variants)}")
    for e, v, p in variants:
        n = sum(1 for s in sites if s[2] == f"{e}::{v}")
        print(f"  {e}::{v}(String) ({p}): built in {n} places")
    print(f"places that build them: {len(sites)}")
    if LIST:
        for p, ln, name, t in sites:
            print(f"      {p}:{ln}: {t}")
    print()

    print("## 6. too_many_arguments allowances")
    total = 0
    for c in crates():
        n = 0
        for p in crate_files(c):
            code = blank(open(p, encoding="utf-8").read())
            n += len(re.findall(r"clippy::too_many_arguments", code))
        total += n
        print(f"  {c}: {n}")
    print(f"  total: {total}")


if __name__ == "__main__":
    main()
