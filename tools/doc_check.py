#!/usr/bin/env python3
"""doc_check.py — the commands and quoted outputs of README.md and docs/ checked against the
program (issue #11), so that the docs cannot drift from what the drivers accept and print.

  tools/doc_check.py --build build [--source .] [--times] [--keep] [FILE.md ...]

Every ```bash block of the files is read and checked statically, whatever its mark:
  * a driver called as build/examples/<dir>/<name> exists in the build, and every --option
    the command gives appears in that driver's --help;
  * a script of the repository (contrib/..., tools/...*.py) exists and, for a Python script,
    every --option appears in its --help;
  * a path of the repository (examples/..., contrib/..., tests/data/..., cmake/...) exists.

Every ```bash block must also be run or say why not: an HTML comment on the line before it
(invisible once rendered) marks it, and a block with neither mark is an error (one line naming
the file and line). The check ends with a count of the blocks run and skipped, and lists the
skipped ones with their reasons.
  <!-- doc-check: run [small="ARGS"] [setup="COMMANDS"] [timeout=S] -->   before a ```bash block
      runs the block with bash (set -e) in a scratch folder that links build/ and the
      repository's folders (a folder per Markdown file: a run block finds what the run blocks
      of its file before it wrote); its output (stdout and stderr) is kept for the next output
      block of the file. A non-zero status is an error, and so is a block that runs past S
      seconds (default 120).
      small="ARGS": the options ARGS are given to every call of a program of the build
      (build/examples/DIR/NAME, build/tests/NAME, also through a variable such as
      S=build/examples/...) that has them in its --help, in place of the same options of the
      command (`--cycles 2` replaces `--cycles 200`), the others appended: a small case of a
      long run, the docs show the real command, the check runs it in seconds. Each option of
      ARGS must be an option of one of the block's programs. (The programs are called through
      a small script that adds ARGS: a block that runs one under valgrind gets the script's
      profile, so such a block takes no small.)
      setup="COMMANDS": run first, in the same folder, for what the block needs and the docs
      made earlier (a sample of a previous section); its output is not kept.
  <!-- doc-check: skip why="REASON" -->                       before a ```bash block
      the block is only checked statically, not run: REASON (not empty) says why — it runs
      for hours, needs a cluster, installs packages, builds the project, ...
  <!-- doc-check: paraview -->                                before a ```bash block
      the ParaView recipe of docs/output.md: not run here but by the ctest paraview_recipe
      (when pvbatch and xvfb-run are installed); counted as skipped.
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

Every relative link outside code blocks must name a file of the repository and, for a Markdown
file, one of its headings (tools/doc_links.py).

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
import time

from doc_links import check_links

REPO_DIRS = ("examples", "contrib", "tools", "tests", "cmake", "docs", "shared", "src", "validation")
DEFAULT_FILES = ("README.md", "docs/*.md", "docs/record/*.md", "examples/long_run/README.md", "contrib/paraview/README.md")
WRAPPERS = {"nohup", "nice", "time", "exec", "env"}
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
MARK = re.compile(r"^<!--\s*doc-check:\s*(.*?)\s*-->\s*$")


class Checker:
    def __init__(self, source, build):
        self.source, self.build = source, build
        self.errors = []
        self.helps = {}
        self.counts = {"commands": 0, "runs": 0, "outputs": 0, "quoted lines": 0}
        self.blocks = {"run": 0, "skipped": 0, "unmarked": 0}
        self.skipped = []  # (where, reason)
        self.times = []  # (where, seconds) of the run blocks

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
                    self.blocks["run"] += 1
                    output = self.run_block(where, body, opts, work)
                elif kind == "skip":
                    why = opts.get("why", "").strip()
                    self.blocks["skipped"] += 1
                    self.skipped.append((where, why))
                    if not why:
                        self.error(where, 'a skip mark needs a reason: <!-- doc-check: skip why="..." -->')
                elif kind == "paraview":
                    self.blocks["skipped"] += 1
                    self.skipped.append((where, "the ParaView recipe: run by the ctest paraview_recipe when pvbatch and xvfb-run are installed"))
                elif kind:
                    self.error(where, "unknown doc-check mark '%s' before a bash block" % mark[0])
                else:
                    self.blocks["unmarked"] += 1
                    self.error(where, 'a bash block neither run nor skipped: put <!-- doc-check: run ... --> or '
                               '<!-- doc-check: skip why="..." --> on the line before it')
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
        start = time.monotonic()
        try:
            return self.run_block_timed(where, body, opts, work)
        finally:
            self.times.append((where, time.monotonic() - start))

    def run_block_timed(self, where, body, opts, work):
        self.counts["runs"] += 1
        text = "\n".join([opts["cmd"]] if "cmd" in opts else body)
        if opts.get("small", "").strip():
            text = self.with_small(where, text, opts["small"], work)
            if text is None:
                return None
        timeout = float(opts.get("timeout", 120))
        if opts.get("setup", "").strip():
            try:
                p = subprocess.run(["bash", "-ec", opts["setup"]], cwd=work, capture_output=True, text=True,
                                   timeout=timeout)
            except subprocess.TimeoutExpired:
                self.error(where, "the block's setup did not finish within %g s" % timeout)
                return None
            if p.returncode != 0:
                self.error(where, "the block's setup exited with status %d:\n%s" % (p.returncode, indent(p.stdout + p.stderr)))
                return None
        try:
            p = subprocess.run(["bash", "-ec", text], cwd=work, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            self.error(where, "the block did not finish within %g s" % timeout)
            return None
        out = p.stdout + p.stderr
        if p.returncode != 0:
            self.error(where, "the block exited with status %d:\n%s" % (p.returncode, indent(out)))
        return out

    def with_small(self, where, text, small, work):
        """The block's text with its programs of the build called through scripts that give them
        the options of `small` (those each has), in place of the same options of the command."""
        groups = option_groups(shlex.split(small))
        if not groups or any(not g[0].startswith("--") for g in groups):
            self.error(where, "small=\"%s\" is not a list of --options" % small)
            return None
        prog_rx = r"(?<![\w/.-])build/((?:examples/[\w.-]+|tests)/[\w.-]+)(?![\w.-]*/)"
        folder = tempfile.mkdtemp(prefix="small_", dir=work)
        used = set()
        for prog in sorted(set(re.findall(prog_rx, text))):
            exe = os.path.join(self.build, prog)
            if not os.access(exe, os.X_OK):
                continue  # the block fails on its own, with the shell's message
            help_text = self.help_text([exe]) or ""
            given = [g for g in groups if re.search(r"(?<![\w-])" + re.escape(option_name(g[0])) + r"(?![\w-])", help_text)]
            used.update(option_name(g[0]) for g in given)
            wrapper = os.path.join(folder, prog)
            os.makedirs(os.path.dirname(wrapper), exist_ok=True)
            with open(wrapper, "w", encoding="utf-8") as f:
                f.write(SMALL_SCRIPT % (sys.executable, exe, [w for g in given for w in g]))
            os.chmod(wrapper, 0o755)
        unknown = [option_name(g[0]) for g in groups if option_name(g[0]) not in used]
        if unknown:
            self.error(where, "small=: %s is an option of none of the block's programs" % ", ".join(unknown))
            return None
        return re.sub(prog_rx, lambda m: os.path.join(folder, m.group(1)), text)

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


# the script through which a run block with small="ARGS" calls a program of the build
SMALL_SCRIPT = """#!%s
import os, sys
exe, small = %r, %r
def groups(words):
    out = []
    for w in words:
        if w.startswith("--") or not out:
            out.append([w])
        else:
            out[-1].append(w)
    return out
names = set(g[0].split("=", 1)[0] for g in groups(small))
args = [w for g in groups(sys.argv[1:]) if g[0].split("=", 1)[0] not in names for w in g]
os.execv(exe, [exe] + args + small)
"""


def option_groups(words):
    """[['--name', values...], ...]: each --option with the words after it up to the next --option."""
    out = []
    for w in words:
        if w.startswith("--") or not out:
            out.append([w])
        else:
            out[-1].append(w)
    return out


def option_name(word):
    return word.split("=", 1)[0]


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
    p.add_argument("--keep", action="store_true", help="keep the scratch folders the run blocks ran in (one per file)")
    p.add_argument("--times", action="store_true", help="print the wall time of each run block")
    p.add_argument("files", nargs="*", help="markdown files (default: README.md, docs/*.md, docs/record/*.md, the READMEs of examples and contrib)")
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
        for n, f in enumerate(files):
            if not os.path.isfile(f):
                print("doc_check: no file '%s'" % f, file=sys.stderr)
                return 2
            # a scratch folder per file: its run blocks see what the ones before them wrote
            scratch = os.path.join(work, "%02d_%s" % (n, os.path.basename(f)[:-3] if f.endswith(".md") else os.path.basename(f)))
            os.mkdir(scratch)
            os.symlink(build, os.path.join(scratch, "build"))
            for d in REPO_DIRS:
                if os.path.isdir(os.path.join(source, d)):
                    os.symlink(os.path.join(source, d), os.path.join(scratch, d))
            c.check_file(os.path.abspath(f), scratch)
    finally:
        if a.keep:
            print("doc_check: scratch folders kept: %s" % work)
        else:
            shutil.rmtree(work, ignore_errors=True)
    link_errors, c.counts["links"] = check_links(files, source)
    c.errors += link_errors
    summary = ", ".join("%d %s" % (v, k) for k, v in c.counts.items())
    for where, why in c.skipped:
        print("doc_check: skipped %s: %s" % (where, why))
    if a.times:
        for where, seconds in c.times:
            print("doc_check: ran %s in %.1f s" % (where, seconds))
    for e in c.errors:
        print("doc_check: " + e)
    print("doc_check: %d bash block(s): %d run, %d skipped, %d with no mark" %
          (sum(c.blocks.values()), c.blocks["run"], c.blocks["skipped"], c.blocks["unmarked"]))
    print("doc_check: %d file(s), %s: %s" % (len(files), summary, "%d disagreement(s)" % len(c.errors) if c.errors else "all agree"))
    return 1 if c.errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
