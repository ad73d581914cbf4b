#!/usr/bin/env python3
"""Every file, function, type and test the docs cite must exist in the sources.

Reads the manuals (docs/*.md, README.md, scenes/README.md, gui/README.md) and checks:
  - backticked paths (`common/render/Camera.h`, `scenes/default.yaml`, `render/LightLanes.h`,
    `Viewer.cpp` beside gui/README.md): a file or folder at the repository root, beside the doc,
    or under one of the source folders; a bare `Foo.h` or `Foo.cpp` anywhere in the sources;
  - backticked names (`WorkDispatcher::service`, `runRender()`, `kNewsDelay`, `LiveRenderer`,
    the test `PhotonGather.AutomaticKKeepsABrightLineThatFixedKBlurs`): every part of the name
    is a word of the sources (common/ master/ slave/ gui/ tests/ scripts/); `Type::member`
    also needs the file that defines Type to hold member;
  - `name` in `File.cpp` and `name` (`File.h`): that file holds the name;
  - relative links, in the manuals and in docs/journal/: the file exists and, when the link
    names a heading (`caustics.md#where-caustic-mapping-fails`), the heading does.
Fenced code blocks are commands with placeholders and made-up outputs: not read.
Prints `doc:line: what is missing` for each, and exits 1 if there is any.

    tests/architecture/doc_citations.py [REPOSITORY]
    tests/architecture/doc_citations.py --self-test    # the checker on a repository of its own
"""
import re
import sys
from pathlib import Path

SOURCE_FOLDERS = ["common", "master", "slave", "gui", "tests", "scripts"]
BUILD_FILES = ["CMakeLists.txt", "CMakePresets.json", "cmake"]  # where targets are named
SOURCE_SUFFIXES = {".h", ".cpp", ".py", ".sh", ".txt", ".cmake", ".in"}
CITED_ROOTS = ("common/", "master/", "slave/", "gui/", "tests/", "scripts/", "scenes/", "docs/")
FILE_SUFFIX = re.compile(r"\.(h|cpp|py|sh|md|yaml|nff|obj|mtl|ply|glb|gltf|png|csv|txt|json)$")
# Qualified names from these namespaces are the libraries' (`std::istream`), not Prism's.
LIBRARY_NAMESPACES = {"std", "glm", "YAML", "CLI"}
# A name or path part that stands for any (`X.h`, `XCommand`, `readX`, `DIR/big-mesh.ply`,
# `glass-ball-SCENE.yaml`): the how-to sections' templates and the commands' arguments.
PLACEHOLDER = re.compile(r"(?:^|[^A-Za-z])X(?:[^a-z]|$)|[a-z]X(?:[^a-z]|$)|(?:^|/)[A-Z]{2,}/|[A-Z]{4,}")

IDENTIFIER = r"[A-Za-z_][A-Za-z0-9_]*"
QUALIFIED_NAME = re.compile(rf"^(?:{IDENTIFIER}::)+~?{IDENTIFIER}(?:\(\))?$")
CALL = re.compile(rf"^({IDENTIFIER})\(\)$")
CAMEL_FUNCTION = re.compile(r"^[a-z][a-z0-9]*(?:[A-Z][a-z0-9]*)+$")  # runRender, tracePhotonPass
CONSTANT = re.compile(r"^k[A-Z][A-Za-z0-9]*$")  # kNewsDelay
TYPE_NAME = re.compile(r"^[A-Z][a-z0-9]+(?:[A-Z][a-z0-9]*)+$")  # LiveRenderer (two humps or more)
TEST_NAME = re.compile(r"^([A-Z][A-Za-z0-9]*)\.([A-Z][A-Za-z0-9]+)$")  # Suite.Test
CODE_SUFFIX = re.compile(r"\.(h|cpp|py|sh)$")
PATH_TOKEN = re.compile(r"^[A-Za-z0-9_.+\-/]+$")
NAME_IN_FILE = re.compile(
    rf"`((?:{IDENTIFIER}::)*{IDENTIFIER}(?:\(\))?)`,? (?:in |\()`([A-Za-z0-9_./]+\.(?:h|cpp))`")
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def source_words(root):
    words = set()
    for entry in SOURCE_FOLDERS + BUILD_FILES:
        top = root / entry
        for path in [top] if top.is_file() else top.rglob("*"):
            if path.is_file() and (path.suffix in SOURCE_SUFFIXES | {".json"} or path.name == "CMakeLists.txt"):
                words.update(re.findall(r"\w+", path.read_text(errors="replace")))
    return words


def source_basenames(root):
    names = set()
    for folder in SOURCE_FOLDERS:
        names.update(p.name for p in (root / folder).rglob("*") if p.is_file())
    return names


def prose_lines(text):
    """(line number, line) for every line outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def inline_code(text):
    """(line number, span) for each backticked span; a span may continue onto the next line."""
    lines = list(prose_lines(text))
    for index, (number, line) in enumerate(lines):
        # Double backticks quote single ones (`` ` ``): drop them before pairing.
        line = re.sub(r"``.*?``", "", line)
        parts = line.split("`")
        for span in parts[1:-1:2]:
            yield number, span
        if len(parts) % 2 == 0 and index + 1 < len(lines):  # an odd backtick: continues below
            following = lines[index + 1][1].split("`", 1)[0]
            yield number, parts[-1] + " " + following


def slug(heading):
    """GitHub's anchor for a heading."""
    text = heading.strip().lower().replace("`", "")
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen = {}
    result = set()
    for _, line in prose_lines(path.read_text()):
        match = re.match(r"^#+\s+(.*)$", line)
        if not match:
            continue
        base = slug(match.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else f"{base}-{count}")
    return result


class Checker:
    def __init__(self, root):
        self.root = root
        self.sources = {
            path: path.read_text(errors="replace")
            for folder in ["common", "master", "slave", "gui"]
            for path in (root / folder).rglob("*")
            if path.suffix in (".h", ".cpp")
        }
        self.declarers = {}  # type or namespace name: the texts of the files that declare it
        declaration = re.compile(  # a definition, not a forward declaration
            r"\b(?:class|struct|namespace|enum class|enum)\s+(?:\w+::)*(\w+)\s*(?:final\s*)?[:{]")
        for text in self.sources.values():
            for owner in set(declaration.findall(text)):
                self.declarers.setdefault(owner, []).append(text)
        self.words = source_words(root)
        self.basenames = source_basenames(root)
        self.anchor_cache = {}
        self.problems = []
        self.checked = {"paths": 0, "names": 0, "links": 0}

    def report(self, doc, line, what):
        self.problems.append(f"{doc.relative_to(self.root)}:{line}: {what}")

    def resolve(self, doc, token):
        """The file or folder a cited path names, or None."""
        token = token.rstrip("/.,:;")
        candidates = [self.root / token, doc.parent / token]
        candidates += [self.root / folder / token for folder in SOURCE_FOLDERS]
        for candidate in candidates:
            for path in [candidate] + [candidate.with_name(candidate.name + s) for s in (".h", ".cpp")]:
                if path.exists():
                    return path
        if "/" not in token and CODE_SUFFIX.search(token) and token in self.basenames:
            return next(p for f in SOURCE_FOLDERS for p in (self.root / f).rglob(token))
        return None

    def path_exists(self, doc, token):
        return self.resolve(doc, token) is not None

    def check_path(self, doc, line, token):
        if any(mark in token for mark in ("*", "<", "{", "...", "…")) or PLACEHOLDER.search(token):
            return  # a pattern or a placeholder
        self.checked["paths"] += 1
        if not self.path_exists(doc, token):
            self.report(doc, line, f"cites `{token}`, which is not in the repository")

    def check_words(self, doc, line, span, words):
        """Whether every word is in the sources (or not Prism's to check); reports the missing."""
        if words[0] in LIBRARY_NAMESPACES or any(PLACEHOLDER.search(w) for w in words):
            return False
        self.checked["names"] += 1
        missing = [w for w in words if w not in self.words]
        if missing:
            self.report(doc, line, f"cites `{span}`: no {', '.join(missing)} in the sources")
        return not missing

    def check_span(self, doc, line, span):
        span = span.strip()
        if not span:
            return
        for token in span.split():
            token = token.strip("()[],;:'\"")
            if token.startswith(CITED_ROOTS) and PATH_TOKEN.match(token):
                self.check_path(doc, line, token)
        if " " in span:
            return  # a command line or an expression: only its paths are citations
        if "/" in span:
            if PATH_TOKEN.match(span) and CODE_SUFFIX.search(span) and not span.startswith(CITED_ROOTS):
                self.check_path(doc, line, span)  # relative to a source folder: `render/LightLanes.h`
            return
        if FILE_SUFFIX.search(span) and PATH_TOKEN.match(span):
            # `.cpp` after `Foo.h` is Foo.cpp; a data file's bare name is an example (`model.glb`)
            # except beside a folder's README, where it is that folder's file (`default.yaml`).
            beside_readme = doc.name == "README.md" and doc.parent not in (self.root, self.root / "docs")
            if not span.startswith(".") and (CODE_SUFFIX.search(span) or beside_readme):
                self.check_path(doc, line, span)
            return
        name = span[:-2] if span.endswith("()") else span
        if QUALIFIED_NAME.match(span):
            parts = [p for p in name.lstrip("~").split("::") if p]
            if self.check_words(doc, line, span, parts):
                self.check_member(doc, line, span, parts)
        elif (test := TEST_NAME.match(span)):
            self.check_words(doc, line, span, [test.group(1), test.group(2)])
        elif CALL.match(span) or CAMEL_FUNCTION.match(name) or CONSTANT.match(name) or TYPE_NAME.match(name):
            self.check_words(doc, line, span, [name])

    def check_member(self, doc, line, span, parts):
        """`Type::member`: a file that defines Type (class, struct, namespace or enum) holds member."""
        owner, member = parts[-2], parts[-1]
        if owner in LIBRARY_NAMESPACES or PLACEHOLDER.search(owner):
            return
        holders = self.declarers.get(owner, [])
        if holders and not any(re.search(rf"\b{re.escape(member)}\b", t) for t in holders):
            self.report(doc, line, f"cites `{span}`: {owner} is defined without {member}")

    def check_pairs(self, doc, text):
        """`name` in `File.cpp` and `name` (`File.h`): the file must hold the name."""
        for number, line in prose_lines(text):
            for name, file in NAME_IN_FILE.findall(line):
                word = (name[:-2] if name.endswith("()") else name).split("::")[-1]
                path = self.resolve(doc, file)
                if path is None or not path.is_file() or PLACEHOLDER.search(word):
                    continue  # a missing file is reported as such
                if not re.search(rf"\b{re.escape(word)}\b", path.read_text(errors="replace")):
                    self.report(doc, number, f"cites `{name}` in `{file}`, which does not hold it")

    def check_links(self, doc, text):
        for number, line in prose_lines(text):
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target):
                    continue  # https:, mailto:
                file_part, _, anchor = target.partition("#")
                self.checked["links"] += 1
                linked = (doc.parent / file_part).resolve() if file_part else doc
                if not linked.exists():
                    self.report(doc, number, f"links to `{target}`, which is not in the repository")
                elif anchor and linked.suffix == ".md":
                    if linked not in self.anchor_cache:
                        self.anchor_cache[linked] = anchors(linked)
                    if anchor not in self.anchor_cache[linked]:
                        self.report(doc, number, f"links to `{target}`: no such heading")

    def check_manual(self, doc):
        text = doc.read_text()
        for number, span in inline_code(text):
            self.check_span(doc, number, span)
        self.check_pairs(doc, text)
        self.check_links(doc, text)


def self_test():
    """The checker itself: a tiny repository whose doc cites one thing of each kind that is
    there and one that is not; only the missing ones, with their lines, may be reported."""
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        (root / "common" / "render").mkdir(parents=True)
        (root / "common" / "render" / "Camera.h").write_text("struct Camera { void generateRays(); };\n")
        (root / "common" / "render" / "Film.h").write_text("class Camera;\nstruct Film { int width; };\n")
        (root / "docs" / "journal").mkdir(parents=True)
        (root / "docs" / "journal" / "2026-01-01-x.md").write_text("[up](../a.md#gone)\n")
        (root / "docs" / "a.md").write_text(
            "# A heading\n"
            "`common/render/Camera.h`, `render/Camera.h`, `Camera::generateRays`, `Camera.h`\n"
            "`common/render/Lens.h` and `Camera::focus`\n"
            "```\n`common/render/InAFence.h`\n```\n"
            "[here](#a-heading), [there](#no-heading), `X.h`, `readX`, `std::istream`\n"
            "`Film::width` and `Film::generateRays`; `width` in `common/render/Film.h`\n"
            "`generateRays` in `Camera.h`, `generateRays` (`common/render/Film.h`)\n"
        )
        for readme in ("README.md", "scenes/README.md", "gui/README.md"):
            (root / readme).parent.mkdir(exist_ok=True)
            (root / readme).write_text("`tracePhotons`\n")
        for folder_name in SOURCE_FOLDERS:
            (root / folder_name).mkdir(exist_ok=True)
        checker = Checker(root)
        for doc in [root / "docs" / "a.md", root / "README.md"]:
            checker.check_manual(doc)
        checker.check_links(root / "docs/journal/2026-01-01-x.md", "[up](../a.md#gone)\n")
        expected = [
            "docs/a.md:3: cites `common/render/Lens.h`, which is not in the repository",
            "docs/a.md:3: cites `Camera::focus`: no focus in the sources",
            "docs/a.md:8: cites `Film::generateRays`: Film is defined without generateRays",
            "docs/a.md:9: cites `generateRays` in `common/render/Film.h`, which does not hold it",
            "docs/a.md:7: links to `#no-heading`: no such heading",
            "README.md:1: cites `tracePhotons`: no tracePhotons in the sources",
            "docs/journal/2026-01-01-x.md:1: links to `../a.md#gone`: no such heading",
        ]
        if checker.problems != expected:
            print("self-test: expected\n  " + "\n  ".join(expected))
            print("got\n  " + "\n  ".join(checker.problems))
            return 1
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]).resolve()
    checker = Checker(root)
    manuals = sorted((root / "docs").glob("*.md"))
    manuals += [root / "README.md", root / "scenes" / "README.md", root / "gui" / "README.md"]
    for doc in manuals:
        checker.check_manual(doc)
    for record in sorted((root / "docs" / "journal").glob("*.md")):
        checker.check_links(record, record.read_text())  # records keep their names as they were
    for problem in checker.problems:
        print(problem)
    print(", ".join(f"{count} {kind}" for kind, count in checker.checked.items()) + " checked")
    if checker.problems:
        print(f"{len(checker.problems)} citations in the docs name nothing in the repository")
        return 1
    print(f"every citation in {len(manuals)} docs names something in the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main())
