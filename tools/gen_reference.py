#!/usr/bin/env python3
"""gen_reference.py — docs/reference.md kept true to the code (issue #38).

  tools/gen_reference.py --source . --build build --write docs/reference.md   regenerate the options
  tools/gen_reference.py --source . --check docs/reference.md [--build build]  check, change nothing
  tools/gen_reference.py --source . --list                                     what the code writes

The options of every installed driver (the list nscd_installed_drivers of examples/CMakeLists.txt)
are read from its --help and written as one table per driver between the markers
`<!-- gen_reference: options begin -->` and `<!-- gen_reference: options end -->` of the page
(--write needs --build: the drivers' binaries, found as build/examples/*/NAME).

The summary.txt keys and CSV columns are read from the sources of examples/ and shared/ (tests
left out), comments stripped, adjacent string literals joined:
  * a summary key is `name = ` at the start of a literal or after a \\n in it, or the first
    argument of `.add("name", ...)` (`.add("name_" + k, ...)` is the pattern `name_<k>`);
  * a CSV header is a literal of three or more snake_case names joined by commas
    ("step,time,contacts\\n"), or a brace list of four or more snake_case string literals
    ({"step", "time", ...}) in a statement that names CsvWriter, cols or columns.
--check fails (exit 1, one line per name) when one of them is not in the page as `name` (in
backticks; a pattern as `name_<k>`), when a driver is missing from it, and, with --build, when
an option of a driver's --help is missing from that driver's table or the table differs from
what --write would write.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

BEGIN, END = "<!-- gen_reference: options begin -->", "<!-- gen_reference: options end -->"
IDENT = r"[a-z][a-z0-9_]*"


def literals(text):
    """The string literals of C++ source `text` (comments skipped), adjacent ones joined, with
    the text between the previous literal and each one (its context)."""
    out, i, n, ctx_start = [], 0, len(text), 0
    last_end = -10
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
        elif c == "'":
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        elif c == '"':
            if text[i - 1:i] == "R" and text[i - 2:i - 1] not in ("_",) and re.match(r'R"([^(]*)\(', text[i - 1:]):
                m = re.match(r'R"([^(]*)\(', text[i - 1:])
                end = text.find(")" + m.group(1) + '"', i)
                i = n if end < 0 else end + len(m.group(1)) + 2
                continue
            j, buf = i + 1, []
            while j < n and text[j] != '"':
                if text[j] == "\\" and j + 1 < n:
                    buf.append({"n": "\n", "t": "\t"}.get(text[j + 1], text[j + 1]))
                    j += 2
                else:
                    buf.append(text[j])
                    j += 1
            s = "".join(buf)
            if out and text[last_end:i].strip() == "":
                out[-1] = (out[-1][0] + s, out[-1][1], out[-1][2])
            else:
                out.append((s, text[ctx_start:i], text[j + 1:j + 80]))
                ctx_start = i
            last_end = j + 1
            i = j + 1
            ctx_start = i
        else:
            i += 1
    return out


def sources(root):
    files = []
    for top in ("examples", "shared"):
        for f in glob.glob(os.path.join(root, top, "**", "*.[ch]pp"), recursive=True):
            if f.endswith("_test.cpp") or "/tests/" in f:
                continue
            files.append(f)
    return sorted(files)


def written_names(root):
    """{'summary': {name: [file, ...]}, 'csv': {...}} read from the sources."""
    found = {"summary": {}, "csv": {}}

    def add(kind, name, f):
        found[kind].setdefault(name, []).append(os.path.relpath(f, root))

    for f in sources(root):
        text = open(f, encoding="utf-8").read()
        lits = literals(text)
        for k, (s, before, after) in enumerate(lits):
            for m in re.finditer(r"(?:^|\n)(" + IDENT + r") =(?: |$)", s):
                add("summary", m.group(1), f)
            if re.search(r"\.add\(\s*$", before):
                if re.match(r"\s*\+", after):
                    add("summary", s + "<k>", f)
                elif re.fullmatch(IDENT, s):
                    add("summary", s, f)
            if re.fullmatch(r"\n?" + IDENT, s) and re.match(r'\s*<<[^;"]*<<\s*"', after) and k + 1 < len(lits) \
                    and lits[k + 1][0].startswith(" = "):
                add("summary", s.lstrip("\n") + "<k>", f)  # "samples_k" << f << " = "
            if re.fullmatch(r"," + IDENT, s) and re.match(r"\s*<<", after):
                add("csv", s[1:] + "<k>", f)  # out << ",mean_k" << k
            if re.fullmatch(r",?" + IDENT + r"(?:," + IDENT + r"){2,},?\n?", s):
                for name in s.strip(",\n").split(","):
                    add("csv", name, f)
        # brace lists of snake_case literals in a statement naming CsvWriter, cols or columns
        clean = re.sub(r"//[^\n]*", "", text)
        for m in re.finditer(r"\{\s*(\"" + IDENT + r"\"(?:\s*,\s*\"" + IDENT + r"\"){3,})\s*\}", clean):
            start = max(clean.rfind(";", 0, m.start()), clean.rfind("{\n", 0, m.start()))
            stmt = clean[start:m.start()]
            if re.search(r"CsvWriter|\bcols\b|columns|\bnames\b", stmt):
                for name in re.findall(r"\"(" + IDENT + r")\"", m.group(1)):
                    add("csv", name, f)
    return found


def installed_drivers(root):
    text = open(os.path.join(root, "examples", "CMakeLists.txt"), encoding="utf-8").read()
    m = re.search(r"set\(nscd_installed_drivers\s+([^)]*?)\s*\)", text)
    if not m:
        sys.exit("gen_reference: no set(nscd_installed_drivers ...) in examples/CMakeLists.txt")
    return m.group(1).split()


def find_binary(build, name):
    hits = [p for p in glob.glob(os.path.join(build, "examples", "*", name)) if os.access(p, os.X_OK)]
    return hits[0] if hits else None


def parse_help(text):
    """(title, [(option, default, description)]) from a Boost.Program_options --help."""
    lines = text.splitlines()
    head = []
    for line in lines:
        if not line.strip():
            break
        head.append(line.strip())
    title = " ".join(head)
    rows, cur = [], None
    for line in lines:
        m = re.match(r"^  (-\w \[ )?(--[\w-]+)( \])?(.*)$", line)
        if m:
            rest = m.group(4)
            parts = re.split(r"\s{2,}", rest.strip(), maxsplit=1) if rest.strip() else [""]
            spec = parts[0] if not rest.startswith("  ") else ""
            desc = parts[1] if len(parts) > 1 else (parts[0] if rest.startswith("  ") else "")
            # a value and default that fill their column leave one space before the description
            full = re.match(r"^((?:arg|\[=arg\(=[^)]*\)\])(?:\s*\(=[^)]*\))?) (?!\(=)(\S.*)$", rest.strip())
            if len(parts) == 1 and not rest.startswith("  ") and full:
                spec, desc = full.group(1), full.group(2)
            default = ""
            d = re.search(r"\(=([^)]*)\)\s*$", spec)
            if d:
                default = d.group(1)
            flag = re.match(r"\[=arg\(=([^)]*)\)\]", spec)
            name = m.group(2)
            if m.group(1):
                name = m.group(1).strip(" [") + ", " + name
            value = "" if not spec else re.sub(r"\s*(\[=arg\(=[^)]*\)\])?\s*(\(=[^)]*\))?\s*$", "", spec)
            if flag:
                value = "[true/false]"
            cur = [name, value, default, desc.strip()]
            rows.append(cur)
        elif cur is not None and line.startswith("    ") and line.strip():
            cur[3] = (cur[3] + " " + line.strip()).strip()
        elif not line.strip():
            cur = None
    return title, rows


def help_of(binary):
    r = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=60)
    return r.stdout


def options_markdown(root, build):
    out = [BEGIN, ""]
    for name in installed_drivers(root):
        b = find_binary(build, name)
        if not b:
            sys.exit(f"gen_reference: driver {name} not built under {build}/examples")
        title, rows = parse_help(help_of(b))
        out.append(f"### `{name}`")
        out.append("")
        out.append(title.replace("|", "\\|"))
        out.append("")
        out.append("| Option | Default | What it does |")
        out.append("|---|---|---|")
        for opt, value, default, desc in rows:
            if opt.endswith("--help") or opt == "--config":
                continue
            default = default.replace(os.path.abspath(build), "BUILD").replace(build, "BUILD")
            default = re.sub(r"^/\S*?/(test-data/)", r"BUILD/\1", default)  # a build of the same tree elsewhere
            if "the machine's cores" in desc:
                default = "cores"  # machine-dependent: the --help shows this machine's count
            o = f"`{opt}" + (f" {value}" if value and value != "arg" else "") + "`"
            desc = desc.replace("|", "\\|").replace("<", "&lt;")  # no HTML tag in a table cell
            out.append(f"| {o} | {('`' + default + '`') if default else ''} | {desc} |")
        out.append("")
    out.append(END)
    return "\n".join(out)


def check(root, page, build):
    text = open(page, encoding="utf-8").read()
    quoted = {re.sub(r"<[^>]*>", "<>", q) for q in re.findall(r"`([^`\n]+)`", text)}
    # a table cell or list item may quote several names: `a`, `b`; or a pattern `name_<k>`
    errors = []
    found = written_names(root)
    for kind, label in (("summary", "summary.txt key"), ("csv", "CSV column")):
        for name, files in sorted(found[kind].items()):
            if re.sub(r"<[^>]*>", "<>", name) not in quoted:
                errors.append(f"{os.path.relpath(page)}: {label} `{name}` (written in {files[0]}) is not in the reference")
    for name in installed_drivers(root):
        if f"### `{name}`" not in text:
            errors.append(f"{os.path.relpath(page)}: driver {name} has no section ### `{name}`")
    if build:
        if BEGIN not in text or END not in text:
            errors.append(f"{os.path.relpath(page)}: no {BEGIN} ... {END} block")
        else:
            now = text[text.index(BEGIN):text.index(END) + len(END)]
            want = options_markdown(root, build)
            if now != want:
                a, b = now.splitlines(), want.splitlines()
                for k in range(max(len(a), len(b))):
                    x = a[k] if k < len(a) else "(end)"
                    y = b[k] if k < len(b) else "(end)"
                    if x != y:
                        errors.append(f"{os.path.relpath(page)}: the options differ from the drivers' --help from "
                                      f"'{x[:90]}' (the --help gives '{y[:90]}'): run tools/gen_reference.py --write")
                        break
    for e in errors:
        print(e)
    n = sum(len(v) for v in found.values())
    print(f"gen_reference: {len(found['summary'])} summary keys, {len(found['csv'])} CSV columns "
          f"({n} uses), {len(installed_drivers(root))} drivers: {len(errors)} missing or stale")
    return 1 if errors else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", default=".")
    ap.add_argument("--build")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", metavar="PAGE")
    g.add_argument("--check", metavar="PAGE")
    g.add_argument("--list", action="store_true")
    a = ap.parse_args()
    root = os.path.abspath(a.source)
    if a.list:
        for kind, names in written_names(root).items():
            for name, files in sorted(names.items()):
                print(f"{kind}\t{name}\t{' '.join(sorted(set(files)))}")
        return 0
    if a.check:
        return check(root, a.check, a.build)
    if not a.build:
        ap.error("--write needs --build")
    text = open(a.write, encoding="utf-8").read()
    block = options_markdown(root, a.build)
    if BEGIN in text and END in text:
        text = text[:text.index(BEGIN)] + block + text[text.index(END) + len(END):]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    open(a.write, "w", encoding="utf-8").write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
