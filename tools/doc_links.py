"""doc_links.py — the relative links of the docs checked (used by doc_check.py): every
[text](path) and [text](path#anchor) outside code blocks names a file of the repository and, for
a Markdown file, one of its headings, so that moving a section cannot leave a link behind.

Anchors follow GitHub's rule: the heading's text (a link's text in place of the link), lower
case, every character but letters, digits, spaces, '-' and '_' dropped, spaces turned into
'-'; a heading met again gets -1, -2, … appended.
"""
import os
import re

LINK = re.compile(r"\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
INLINE_LINK = re.compile(r"\[([^\]]*)\]\([^)]*\)")


def slug(heading):
    text = INLINE_LINK.sub(r"\1", heading).strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def outside_code(path):
    """(line number, line) of a Markdown file, the lines of ``` blocks left out."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if not fenced:
                yield n, line


class Anchors:
    def __init__(self):
        self.known = {}

    def of(self, path):
        if path not in self.known:
            seen, found = {}, set()
            for _, line in outside_code(path):
                m = HEADING.match(line)
                if not m:
                    continue
                s = slug(m.group(2))
                k = seen.get(s, 0)
                seen[s] = k + 1
                found.add(s if k == 0 else "%s-%d" % (s, k))
            self.known[path] = found
        return self.known[path]


def check_links(files, source):
    """One line per link of `files` that names no file of `source`, or no heading of it; and
    the number of links checked."""
    errors, anchors, checked = [], Anchors(), 0
    for f in files:
        rel = os.path.relpath(f, source)
        for n, line in outside_code(f):
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-z]+:", target):  # http:, https:, mailto:
                    continue
                checked += 1
                path, _, anchor = target.partition("#")
                to = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
                if not os.path.exists(to):
                    errors.append("%s:%d: the link '%s' names no file" % (rel, n, target))
                elif anchor and to.endswith(".md") and anchor not in anchors.of(to):
                    errors.append("%s:%d: the link '%s' names no heading of %s" %
                                  (rel, n, target, os.path.relpath(to, source)))
    return errors, checked
