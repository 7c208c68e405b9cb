#!/usr/bin/env python3
"""doc_check.py — the commands and quoted outputs of README.md and docs/ checked against the
program (issue #11), so that the docs cannot drift from what the drivers accept and print.

  tools/doc_check.py --build build [--source .] [FILE.md ...]

Every ```bash block of the files is read (no marker needed) and checked statically:
  * a driver called as build/examples/<dir>/<name> exists in the build, and every --option
    the command gives appears in that driver's --help;
  * a script of the repository (contrib/..., tools/...*.py) exists and, for a Python script,
    every --option appears in its --help;
  * a path of the repository (examples/..., contrib/..., tests/data/..., cmake/...) exists.

Blocks marked with an HTML comment on the line before them (invisible once rendered) are run
and compared:
  <!-- doc-check: run [small="ARGS"] [timeout=S] -->        before a ```bash block
      runs the block with bash (set -e) in a scratch folder that links build/ and the
      repository's folders, ARGS appended to every driver call (a small case of a long run:
      the docs show the real command, the check runs it in seconds); its output (stdout and
      stderr) is kept for the next output block of the file. A non-zero status is an error.
  <!-- doc-check: output [format] [tol=R] -->                 before a ```text block
      every line of the block must match a line of that output, in the same order (lines of
      the output in between are allowed). `...` in a quoted line stands for any text; a token
      written ~X (a wall time, an ETA) stands for any token. Numbers must agree within the
      relative tolerance R (default 0.02); with `format` only the text between the numbers is
      compared (a full-size run's output quoted in the docs, checked on the small case).

  <!-- doc-check: compile NAME -->                           before a ```cpp block
      the program is built with the project (tests/docs/CMakeLists.txt extracts it with
      --extract-cpp into build/tests/docs/NAME.cpp, linked to nscd::nscd): a run block can run
      it as build/tests/docs/NAME.
  A run block may give cmd="COMMAND" to run COMMAND instead of its own lines (a block that
  shows how to build and run a program of the docs runs that program as the build made it).

Exit status: 0 when everything agrees, 1 with one line per disagreement, 2 for bad usage.
"""
import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

REPO_DIRS = ("examples", "contrib", "tools", "tests", "cmake", "docs", "shared", "src", "validation")
DEFAULT_FILES = ("README.md", "docs/*.md", "examples/long_run/README.md", "contrib/paraview/README.md")
WRAPPERS = {"nohup", "nice", "time", "exec", "env"}
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
MARK = re.compile(r"^<!--\s*doc-check:\s*(.*?)\s*-->\s*$")


class Checker:
    def __init__(self, source, build):
        self.source, self.build = source, build
        self.errors = []
        self.helps = {}
        self.counts = {"commands": 0, "runs": 0, "outputs": 0, "quoted lines": 0}

    def error(self, where, message):
        self.errors.append("%s: %s" % (where, message))

    # --- --help texts ----------------------------------------------------------------------
    def help_text(self, argv):
        key = tuple(argv)
        if key not in self.helps:
            try:
                p = subprocess.run(list(argv) + ["--help"], capture_output=True, text=True, timeout=60)
                self.helps[key] = p.stdout + p.stderr
            except (OSError, subprocess.TimeoutExpired) as e:
                self.helps[key] = None
                self.helps[key + ("error",)] = str(e)
        return self.helps[key]

    # --- static checks of one command ----------------------------------------------------------
    def check_command(self, where, words):
        while words and (words[0] in WRAPPERS or re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0])):
            words = words[1:]
        if words[:2] == ["xvfb-run", "-a"]:
            words = words[2:]
        if words and words[0] == "timeout":
            words = words[2:]
        if words and words[0] in ("pvbatch", "python3", "/usr/bin/python3"):
            words = words[1:]
        if not words:
            return
        prog, args = words[0], words[1:]
        for a in args:
            self.check_path(where, a)
        if prog.startswith("build/examples/"):
            self.counts["commands"] += 1
            exe = os.path.join(self.build, prog[len("build/"):])
            if not os.access(exe, os.X_OK):
                self.error(where, "'%s' is not a driver of the build (%s)" % (prog, exe))
                return
            self.check_options(where, prog, [exe], args)
        elif prog.split("/")[0] in ("contrib", "tools") and prog.endswith(".py"):
            self.counts["commands"] += 1
            script = os.path.join(self.source, prog)
            if not os.path.isfile(script):
                self.error(where, "no script '%s' in the repository" % prog)
                return
            self.check_options(where, prog, [sys.executable, script], args)
        elif prog.split("/")[0] in REPO_DIRS:
            self.check_path(where, prog)

    def check_options(self, where, prog, argv, args):
        text = self.help_text(argv)
        if text is None:
            self.error(where, "'%s --help' could not be run" % prog)
            return
        for a in args:
            if a.startswith("--") and len(a) > 2:
                name = a.split("=", 1)[0]
                if not re.search(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", text):
                    self.error(where, "'%s' has no option %s (not in its --help)" % (prog, name))

    def check_path(self, where, token):
        t = token.rstrip(".,;:)")
        head = t.split("/")[0]
        if head not in REPO_DIRS or "/" not in t or "$" in t:
            return
        if any(c in t for c in "*?["):
            if not glob.glob(os.path.join(self.source, t)):
                self.error(where, "no file matches '%s' in the repository" % t)
        elif not os.path.exists(os.path.join(self.source, t)):
            self.error(where, "no file or folder '%s' in the repository" % t)

    # --- the blocks of one file -----------------------------------------------------------------
    def check_file(self, path, work):
        rel = os.path.relpath(path, self.source)
        lines = open(path, encoding="utf-8").read().split("\n")
        blocks, i, mark = [], 0, None
        while i < len(lines):
            m = MARK.match(lines[i].strip())
            if m:
                mark = (m.group(1), i + 1)
                i += 1
                continue
            f = re.match(r"^\s*```(\w*)\s*$", lines[i])
            if f:
                start, j = i + 1, i + 1
                while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
                    j += 1
                blocks.append((f.group(1), start, lines[start:j], mark if mark and mark[1] == i else None))
                mark, i = None, j + 1
                continue
            if lines[i].strip():
                mark = None
            i += 1
        output = None
        env = {}
        for lang, start, body, mark in blocks:
            where = "%s:%d" % (rel, start)
            kind, opts = parse_mark(mark[0]) if mark else (None, {})
            if lang in ("bash", "sh"):
                for cmd_line, n in logical_lines(body):
                    for words in commands(cmd_line, env):
                        self.check_command("%s:%d" % (rel, start + n + 1), words)
                if kind == "run":
                    output = self.run_block(where, body, opts, work)
            elif kind == "output":
                self.counts["outputs"] += 1
                if output is None:
                    self.error(where, "an output block with no run block before it")
                else:
                    self.compare(where, body, output, opts)
            elif kind == "compile" and lang == "cpp":
                pass  # built by tests/docs/CMakeLists.txt (--extract-cpp)
            elif kind:
                self.error(where, "unknown doc-check mark '%s' (or not before a block of its kind)" % mark[0])

    def run_block(self, where, body, opts, work):
        self.counts["runs"] += 1
        small = opts.get("small", "")
        script = []
        for line in ([opts["cmd"]] if "cmd" in opts else body):
            if small:
                line = re.sub(r"(build/examples/[\w.-]+/[\w.-]+)", lambda m: m.group(1) + " " + small, line)
            script.append(line)
        try:
            p = subprocess.run(["bash", "-ec", "\n".join(script)], cwd=work, capture_output=True, text=True,
                               timeout=float(opts.get("timeout", 120)))
        except subprocess.TimeoutExpired:
            self.error(where, "the block did not finish within %s s" % opts.get("timeout", 120))
            return None
        out = p.stdout + p.stderr
        if p.returncode != 0:
            self.error(where, "the block exited with status %d:\n%s" % (p.returncode, indent(out)))
        return out

    def compare(self, where, quoted, output, opts):
        tol = float(opts.get("tol", 0.02))
        only_format = "format" in opts
        out_lines = output.split("\n")
        at = 0
        for k, q in enumerate(quoted):
            if not q.strip() or q.strip() in ("...", "…"):
                continue
            self.counts["quoted lines"] += 1
            rx, numbers = line_pattern(q)
            found = None
            for j in range(at, len(out_lines)):
                m = rx.match(out_lines[j])
                if m and (only_format or numbers_agree(numbers, m.groups(), tol)):
                    found = j
                    break
            if found is None:
                near = [l for l in out_lines if rx.match(l)]
                hint = ("closest line: " + near[0]) if near else "no line of that form"
                self.error("%s+%d" % (where, k), "quoted output '%s' not printed by the run (%s%s)" %
                           (q.strip(), hint, "" if only_format else ", tolerance %g" % tol))
            else:
                at = found + 1


def extract_cpp(files, out_dir):
    """Writes each ```cpp block marked `doc-check: compile NAME` to out_dir/NAME.cpp (only when
    its text changed, so that the build does not redo it); prints the names."""
    os.makedirs(out_dir, exist_ok=True)
    names = []
    for path in files:
        lines = open(path, encoding="utf-8").read().split("\n")
        for i, line in enumerate(lines):
            m = MARK.match(line.strip())
            if not m or i + 1 >= len(lines) or not re.match(r"^\s*```cpp\s*$", lines[i + 1]):
                continue
            kind, opts = parse_mark(m.group(1))
            if kind != "compile":
                continue
            name = next(iter(opts), "")
            if not re.fullmatch(r"[A-Za-z0-9_]+", name):
                raise SystemExit("doc_check: %s:%d: 'doc-check: compile' needs a NAME of letters, digits and _" % (path, i + 1))
            j = i + 2
            while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
                j += 1
            text = "// extracted from %s by tools/doc_check.py --extract-cpp: edit the doc, not this file\n" % \
                os.path.basename(path) + "\n".join(lines[i + 2:j]) + "\n"
            target = os.path.join(out_dir, name + ".cpp")
            if not os.path.isfile(target) or open(target, encoding="utf-8").read() != text:
                with open(target, "w", encoding="utf-8") as f:
                    f.write(text)
            names.append(name)
    print(";".join(names))


def parse_mark(text):
    words = shlex.split(text)
    if not words:
        return None, {}
    opts = {}
    for w in words[1:]:
        k, _, v = w.partition("=")
        opts[k] = v
    return words[0], opts


def logical_lines(body):
    """(line, index) with continuation lines joined."""
    out, cur, first = [], "", None
    for n, line in enumerate(body):
        if first is None:
            first = n
        if line.rstrip().endswith("\\"):
            cur += line.rstrip()[:-1] + " "
            continue
        out.append((cur + line, first))
        cur, first = "", None
    if cur:
        out.append((cur, first))
    return out


def commands(line, env):
    """The simple commands of a shell line, as word lists ($VAR expanded from `env`, as the
    shell would split an unquoted expansion)."""
    line = re.sub(r"\$\{?([A-Za-z_][A-Za-z0-9_]*)\}?", lambda m: env.get(m.group(1), m.group(0)), line)
    try:
        lex = shlex.shlex(line, posix=True, punctuation_chars=";&|()<>")
        lex.whitespace_split = True
        lex.commenters = "#"
        tokens = list(lex)
    except ValueError:
        return []
    cmds, cur = [], []
    for t in tokens:
        if t and all(c in ";&|()<>" for c in t):
            if cur:
                cmds.append(cur)
            cur = []
            if t in (">", "<", ">>", "2>", "&>"):
                cur = ["__redirect__"]
            continue
        cur.append(t)
    if cur:
        cmds.append(cur)
    result = []
    for c in cmds:
        c = [w for w in c if w != "__redirect__"] if c[0] != "__redirect__" else []
        if len(c) == 1 and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", c[0]):
            k, _, v = c[0].partition("=")
            env[k] = v
            continue
        if c:
            result.append(c)
    return result


def line_pattern(q):
    """A regex for a quoted output line, and which of its groups are numbers to compare."""
    parts, numbers = [], []
    for tok in re.split(r"(\s+)", q.strip()):
        if not tok:
            continue
        if tok.isspace():
            parts.append(r"\s+")
        else:
            # ~X (up to a closing bracket or punctuation) is any token: "(~55.9s)", "~2m53s,"
            pieces = re.split(r"(~[^\s),;]+|\.\.\.|…|" + NUMBER + ")", tok)
            for piece in pieces:
                if not piece:
                    continue
                if piece.startswith("~"):
                    parts.append(r"[^\s),;]+")
                elif piece in ("...", "…"):
                    parts.append(".*?")
                elif re.fullmatch(NUMBER, piece):
                    parts.append("(" + NUMBER + ")")
                    numbers.append(float(piece))
                else:
                    parts.append(re.escape(piece))
    return re.compile(r"^\s*" + "".join(parts) + r"\s*$"), numbers


def numbers_agree(expected, got, tol):
    for e, g in zip(expected, got):
        g = float(g)
        if abs(e - g) > tol * max(abs(e), abs(g)) + 1e-12:
            return False
    return True


def indent(text, n=40):
    lines = text.strip().split("\n")
    return "\n".join("    " + l for l in lines[-n:])


def main(argv):
    p = argparse.ArgumentParser(description="Check the commands and quoted outputs of README.md and docs/ against the program.")
    p.add_argument("--build", help="the nscd build folder (with build/examples/...)")
    p.add_argument("--extract-cpp", metavar="DIR", help="only write the ```cpp blocks marked 'compile NAME' to DIR/NAME.cpp")
    p.add_argument("--source", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                   help="the repository (default: this script's)")
    p.add_argument("--keep", action="store_true", help="keep the scratch folder the run blocks ran in")
    p.add_argument("files", nargs="*", help="markdown files (default: README.md, docs/*.md, the READMEs of examples and contrib)")
    a = p.parse_args(argv)
    source = os.path.abspath(a.source)
    files = a.files or sorted(f for pat in DEFAULT_FILES for f in glob.glob(os.path.join(source, pat)))
    if a.extract_cpp:
        extract_cpp(files, a.extract_cpp)
        return 0
    if not a.build:
        print("doc_check: --build is required", file=sys.stderr)
        return 2
    build = os.path.abspath(a.build)
    if not os.path.isdir(os.path.join(build, "examples")):
        print("doc_check: '%s' is not an nscd build with its examples (no examples/ in it)" % build, file=sys.stderr)
        return 2
    c = Checker(source, build)
    work = tempfile.mkdtemp(prefix="nscd_doc_check_")
    try:
        os.symlink(build, os.path.join(work, "build"))
        for d in REPO_DIRS:
            if os.path.isdir(os.path.join(source, d)):
                os.symlink(os.path.join(source, d), os.path.join(work, d))
        for f in files:
            if not os.path.isfile(f):
                print("doc_check: no file '%s'" % f, file=sys.stderr)
                return 2
            c.check_file(os.path.abspath(f), work)
    finally:
        if a.keep:
            print("doc_check: scratch folder kept: %s" % work)
        else:
            shutil.rmtree(work, ignore_errors=True)
    summary = ", ".join("%d %s" % (v, k) for k, v in c.counts.items())
    for e in c.errors:
        print("doc_check: " + e)
    print("doc_check: %d file(s), %s: %s" % (len(files), summary, "%d disagreement(s)" % len(c.errors) if c.errors else "all agree"))
    return 1 if c.errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
