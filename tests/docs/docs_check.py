#!/usr/bin/python3
"""Docs true to the tree: fails (exit 1) on
- a machine path in a tracked text file (/work/..., /home/<user>, ../shared/): the repository
  must stand alone;
- a markdown link to a file or folder that does not exist (relative to the .md file);
- a capitalised markdown file name (DESIGN.md, NOTES.md ...) cited anywhere that no file in the
  tree is called.
Usage: docs_check.py ROOT   (the files: `git ls-files` when ROOT is a git checkout, else a walk)
"""
import os
import re
import subprocess
import sys

MACHINE_PATH = re.compile(r"(?<![\w.$}])(/work/|/home/[a-z_]\w*|\.\./shared/)")
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
CITED_MD = re.compile(r"\b([A-Z][A-Z0-9_]*\.md)\b")
SKIP_DIRS = ("tests/data/", "assets/", "fuzz/corpus/")
SELF = "tests/docs/docs_check.py"


def tracked(root, *extra):
    """The checkout's files (tracked; with "--others", also new files git does not ignore)."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", *extra, "--exclude-standard"],
                             capture_output=True, text=True, check=True).stdout
        return [f for f in out.splitlines() if os.path.isfile(os.path.join(root, f))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(root):
            dirs[:] = [x for x in dirs if not x.startswith((".", "build"))]
            files += [os.path.relpath(os.path.join(d, n), root) for n in names]
        return files


def text_of(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except (UnicodeDecodeError, OSError):
        return None  # binary


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    files = [f for f in tracked(root) if not f.startswith(SKIP_DIRS) and f != SELF]
    names = {os.path.basename(f) for f in tracked(root) + tracked(root, "--others")}
    problems = []
    for f in files:
        text = text_of(os.path.join(root, f))
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            m = MACHINE_PATH.search(line)
            if m:
                problems.append(f"{f}:{n}: machine path {m.group(1)!r}: {line.strip()[:100]}")
            for cited in CITED_MD.findall(line):
                if cited not in names:
                    problems.append(f"{f}:{n}: cites {cited}, which is not in the repository")
            if f.endswith(".md"):
                for target in LINK.findall(line):
                    if re.match(r"^(https?:|mailto:|#)", target):
                        continue
                    path = os.path.normpath(os.path.join(root, os.path.dirname(f),
                                                         target.split("#")[0]))
                    if not os.path.exists(path):
                        problems.append(f"{f}:{n}: link to {target}, which does not exist")
    for p in problems:
        print(p)
    print(f"docs_check: {len(files)} files, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
