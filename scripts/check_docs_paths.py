#!/usr/bin/env python3
"""Reports every repository path that the documentation or a source comment names but that
does not exist, so that a moved or deleted file cannot leave a dangling reference behind.

    scripts/check_docs_paths.py [REPO]      (REPO defaults to this script's repository)

Scanned:
  - README.md, docs/*.md and gallery/README.md: relative Markdown links and images (resolved
    from the file's folder; an #anchor into a Markdown file must name one of its headings, as
    GitHub spells them) and every path-like word that starts at a top-level folder of the
    repository (app/run/run_job.h, tests/app/fit_test.cpp, assets/scenes/x.json, docs/scene.md,
    scripts/setup, ...) or is ./ followed by one (./scripts/test), in prose, code spans and
    code blocks alike.
  - the comments of the C++ sources (// and /* */) and the # comments of the CMake files in
    base/ sim/ analysis/ render/ chart/ app/ bench/ tests/: the same path-like words.
A path exists if the file or folder does, or if it names a program by its source
(bench/sparse_solver_bench for bench/sparse_solver_bench.cpp); a {a,b} alternative is checked
as each of its paths.
Not checked: URLs; output paths (out/..., build/..., build-sanitize/, /usr/..., DIR/...), which
never start at a top-level folder of the source tree; other relative words (../shared/… beside
the repository, a scene's ../meshes/…, ./prog in a build folder); placeholders (a part in <...>,
a $variable, a part in capitals: SCENE.json, frame_N.png); glob patterns (*, ?); elisions
(..., …).
Prints one line per dangling path (file:line: path) and exits 1 if there is any, else 0.
Python 3 standard library only.
"""

import os
import re
import sys

# Folders at the top of the source tree that a repository path starts with.
TOP_FOLDERS = ("analysis", "app", "assets", "base", "bench", "chart", "cmake", "docs", "gallery",
               "render", "scripts", "sim", "tests")
DOC_FILES = ("README.md", "gallery/README.md")
DOC_FOLDERS = ("docs",)
SOURCE_FOLDERS = ("base", "sim", "analysis", "render", "chart", "app", "bench", "tests")
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".c", ".inl")
# Files in capitals that are real names, not placeholders.
REAL_CAPITALS = {"README", "LICENSE", "CHANGELOG"}

URL = re.compile(r"\b[a-zA-Z][a-zA-Z0-9+.-]*://\S+|\bwww\.\S+|\bmailto:\S+")
# A path-like word: a top-level folder, a slash, then path characters. Not preceded by a path
# character, so build/tests/x or out/gallery/x do not yield tests/x or gallery/x.
PATH_CHARS = r"[\w.+\-/*?{},<>…$]"
REPO_PATH = re.compile(r"(?<![\w./\-~$@:])((?:%s)/%s*)" % ("|".join(TOP_FOLDERS), PATH_CHARS))
RELATIVE_PATH = re.compile(r"(?<![\w./\-~$@:])(\./%s+)" % PATH_CHARS)
MD_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
CAPITAL_WORD = re.compile(r"(?:^|[_\-.])(?:[A-Z]{2,}[0-9]*|[A-Z])(?=$|[_\-.])")


def is_placeholder(path):
    """True for paths that stand for others: globs, elisions, <name>, $var, CAPITALS."""
    if any(c in path for c in "*?<>…$") or "..." in path:
        return True
    for part in path.split("/"):
        stem = part.split(".")[0]
        if stem in REAL_CAPITALS:
            continue
        if CAPITAL_WORD.search(part):
            return True
    return False


def clean(path):
    """Strips what follows a path in prose: sentence punctuation, a line number, a comma
    (one inside a {a,b} alternative stays)."""
    depth = 0
    for k, c in enumerate(path):
        depth += (c == "{") - (c == "}")
        if c == "," and depth == 0:
            path = path[:k]
            break
    path = re.sub(r":\d+(?:-\d+)?$", "", path)
    while path and path[-1] in ".,;:)!'\"`":
        path = path[:-1]
    return path


def alternatives(path):
    """The paths a {a,b} alternative stands for: sim/x.{h,cpp} → sim/x.h, sim/x.cpp."""
    match = re.search(r"\{([^{}]*)\}", path)
    if not match:
        return [path]
    return [p for option in match.group(1).split(",")
            for p in alternatives(path[:match.start()] + option + path[match.end():])]


def inside(repo, path):
    """Whether `path` (absolute, normalised) lies in the repository."""
    return os.path.commonpath([path, repo]) == repo


def exists(repo, path):
    """Whether the repository path `path` exists: a file or folder, or a program built from
    `path`.cpp (bench/sparse_solver_bench names the benchmark of bench/sparse_solver_bench.cpp)."""
    full = os.path.join(repo, path)
    return os.path.exists(full) or os.path.isfile(full + ".cpp")


def words(text):
    """The path-like words of a text: repository paths and ./ paths."""
    text = URL.sub(" ", text)
    for match in REPO_PATH.finditer(text):
        yield match.group(1)
    for match in RELATIVE_PATH.finditer(text):
        yield match.group(1)


def check_words(repo, rel_file, line_no, text, findings):
    """Checks the path-like words of `text`: those that start at a top-level folder, and ./x
    when x does (./scripts/setup), are paths from the repository's root. Other relative words
    are not checked: ../x in prose is beside the repository (../shared/…) or relative to a
    scene file, and ./prog in a command is a program of the folder the command runs in."""
    for word in words(text):
        path = clean(word)
        if path.startswith("./"):
            path = path[2:]
            if not REPO_PATH.fullmatch(path):
                continue
        elif path.startswith("."):
            continue
        for alternative in alternatives(path):
            if alternative and not is_placeholder(alternative) and not exists(repo, alternative):
                findings.append((rel_file, line_no, alternative))


def slug(heading):
    """GitHub's anchor of a Markdown heading: the rendered text in lower case, without
    punctuation but - and _, spaces as -."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip())  # links: their text
    text = text.replace("`", "").replace("*", "")
    text = "".join(c for c in text.lower() if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors_of(repo, rel_file, cache={}):
    """The anchors of a Markdown file's headings (GitHub numbers repeats: x, x-1, x-2)."""
    if rel_file not in cache:
        anchors, fenced = set(), False
        with open(os.path.join(repo, rel_file), encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                match = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
                if match:
                    anchor, k = slug(match.group(1)), 1
                    while anchor in anchors:
                        anchor = "%s-%d" % (slug(match.group(1)), k)
                        k += 1
                    anchors.add(anchor)
        cache[rel_file] = anchors
    return cache[rel_file]


def check_markdown(repo, rel_file, findings):
    base_dir = os.path.dirname(rel_file)
    with open(os.path.join(repo, rel_file), encoding="utf-8") as f:
        lines = f.read().split("\n")
    for line_no, line in enumerate(lines, 1):
        for match in MD_LINK.finditer(line):
            target = match.group(1)
            if URL.match(target) or target.startswith("mailto:"):
                continue
            path, _, anchor = target.partition("#")
            if is_placeholder(path):
                continue
            full = os.path.normpath(os.path.join(repo, base_dir, path)) if path else \
                os.path.join(repo, rel_file)
            if not inside(repo, full) or not os.path.exists(full):
                findings.append((rel_file, line_no, target + " (link)"))
            elif anchor and full.endswith(".md") and \
                    anchor not in anchors_of(repo, os.path.relpath(full, repo)):
                findings.append((rel_file, line_no, target + " (link: no such heading)"))
        # The words outside link targets: a link's target was checked above.
        text = MD_LINK.sub(lambda m: m.group(0).split("](")[0], line)
        check_words(repo, rel_file, line_no, text, findings)


def comments_of_cpp(text):
    """Yields (line number, comment text) for every // and /* */ comment of a C++ source,
    skipping string and character literals, raw strings included."""
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            yield line, text[i + 2:end]
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end
            for k, part in enumerate(text[i + 2:end].split("\n")):
                yield line + k, part
            line += text.count("\n", i, end)
            i = end + 2
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum()
                                                                      or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delimiter = text[i + 2:open_paren]
            end = text.find(")" + delimiter + '"', open_paren)
            end = n if end < 0 else end + len(delimiter) + 2
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():
                i += 1  # a digit separator (1'000), not a character literal
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        else:
            i += 1


def comments_of_cmake(text):
    """Yields (line number, comment text) for the # comments of a CMake file (a # inside a
    quoted argument is not one)."""
    for line_no, line in enumerate(text.split("\n"), 1):
        quoted = False
        for k, c in enumerate(line):
            if c == '"' and (k == 0 or line[k - 1] != "\\"):
                quoted = not quoted
            elif c == "#" and not quoted:
                yield line_no, line[k + 1:]
                break


def main():
    repo = os.path.abspath(sys.argv[1] if len(sys.argv) > 1
                           else os.path.join(os.path.dirname(__file__), ".."))
    findings = []
    docs = [p for p in DOC_FILES if os.path.isfile(os.path.join(repo, p))]
    for folder in DOC_FOLDERS:
        for name in sorted(os.listdir(os.path.join(repo, folder))):
            if name.endswith(".md"):
                docs.append(folder + "/" + name)
    for rel_file in docs:
        check_markdown(repo, rel_file, findings)

    for folder in SOURCE_FOLDERS:
        for root, dirs, files in os.walk(os.path.join(repo, folder)):
            dirs.sort()
            for name in sorted(files):
                rel_file = os.path.relpath(os.path.join(root, name), repo)
                if name.endswith(SOURCE_SUFFIXES):
                    comments = comments_of_cpp
                elif name == "CMakeLists.txt" or name.endswith(".cmake"):
                    comments = comments_of_cmake
                else:
                    continue
                with open(os.path.join(repo, rel_file), encoding="utf-8", errors="replace") as f:
                    text = f.read()
                for line_no, comment in comments(text):
                    check_words(repo, rel_file, line_no, comment, findings)

    for rel_file, line_no, path in findings:
        print("%s:%d: %s does not exist" % (rel_file, line_no, path))
    if findings:
        print("%d dangling path(s) in the docs and comments" % len(findings), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
