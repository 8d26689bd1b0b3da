#!/usr/bin/env python3
"""Checks the documents: every relative link resolves, every decision record opens
with its five-line header, docs/decisions/README.md's table matches the headers, and
ARCHITECTURE.md's table of the core's public API names exactly what
crates/primdecomp/src/lib.rs makes public (and the file stays a five-minute read),
every file and core module a record's `Code:` line names (before any "was")
still exists, and docs/modules.md names every file of the core and no file it lacks.

    python3 scripts/check_docs.py           # check; exit 1 with one line per problem
    python3 scripts/check_docs.py --write   # rewrite the README's table from the headers

A link resolves when its file exists (relative to the linking file) and, for an
anchor into a Markdown file, a heading of that file has the anchor's GitHub slug.
A record's header is lines 3 to 7: `Decision:`, `Status:`, `Effect:`, `Code:`,
`Measurements:` (line 1 its title, line 2 blank).
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DECISIONS = ROOT / "docs" / "decisions"
FIELDS = ("Decision:", "Status:", "Effect:", "Code:", "Measurements:")
TABLE_HEAD = "| record | decision | status |\n|---|---|---|\n"
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^(```|~~~)")
LIB = ROOT / "crates" / "primdecomp" / "src" / "lib.rs"
ARCH = ROOT / "ARCHITECTURE.md"
API_HEADING = "## The core's public API"
ARCH_MAX_LINES = 250
IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def documents():
    """The Markdown files a reader opens: docs/, the top-level and per-folder READMEs."""
    files = sorted((ROOT / "docs").rglob("*.md"))
    files += [ROOT / "README.md", ROOT / "ARCHITECTURE.md"]
    for sub in ("fuzz", "tests", "benches", "crates"):
        files += sorted(p for p in (ROOT / sub).rglob("README.md") if not skipped(p))
    return [f for f in files if f.exists()]


def skipped(path):
    """Build outputs and installed packages: not ours to check."""
    rel = path.relative_to(ROOT).parts
    return any(part in ("target", "node_modules") or part.startswith(".") for part in rel)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, out, fenced = {}, set(), False
        for line in path.read_text(encoding="utf-8").splitlines():
            if FENCE.match(line):
                fenced = not fenced
            if fenced or not line.startswith("#"):
                continue
            base = slug(line.lstrip("#"))
            n = seen.get(base, 0)
            seen[base] = n + 1
            out.add(base if n == 0 else f"{base}-{n}")
        cache[path] = out
    return cache[path]


def link_problems(path):
    problems, fenced = [], False
    for no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
        if fenced:
            continue
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):
                continue
            file, _, anchor = target.partition("#")
            dest = (path.parent / file).resolve() if file else path
            where = f"{path.relative_to(ROOT)}:{no}: {target}"
            if not dest.exists():
                problems.append(f"{where}: no such file")
            elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                problems.append(f"{where}: no heading with that anchor")
    return problems


def header(path):
    """The five header values of a record, or None where it has none."""
    lines = path.read_text(encoding="utf-8").splitlines()
    if len(lines) < 7 or lines[1] != "":
        return None
    values = []
    for field, line in zip(FIELDS, lines[2:7]):
        if not line.startswith(field + " "):
            return None
        values.append(line[len(field) + 1 :].strip())
    return lines[0].lstrip("# ").strip(), values


def records():
    """Every record: the top-level ones the table lists, and the cut's steps."""
    top = sorted(p for p in DECISIONS.glob("*.md") if p.name != "README.md")
    return top, sorted((DECISIONS / "cut-steps").glob("*.md"))


CORE = ROOT / "crates" / "primdecomp" / "src"
CODE_TOKEN = re.compile(r"`([^`\s]+)`")
MODULE_PATH = re.compile(r"^[a-z_][a-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)+$")


def source_files(cache=[]):
    """Every file of the repository but build outputs, as paths relative to ROOT."""
    if not cache:
        for p in ROOT.rglob("*"):
            if p.is_file() and not skipped(p):
                cache.append(p.relative_to(ROOT).as_posix())
    return cache


def file_exists(name):
    """A path as records write it: from the root, or the tail of a path (`cut/tree.rs`)."""
    name = name.rstrip("/")
    if (ROOT / name).exists():
        return True
    return any(f == name or f.endswith("/" + name) or ("/" + name + "/") in f
               for f in source_files())


def spelled_files(token):
    """The files a token names: `dir/*` is the folder, `src/{a,b}.rs` two files, and
    `file.rs::name` the file, which must also name the item."""
    token, _, item = token.partition("::")
    token = token.removesuffix("/*")
    m = re.match(r"^(.*)\{([^}]*)\}(.*)$", token)
    names = [m[1] + part + m[3] for part in m[2].split(",")] if m else [token]
    # A file that exists but no longer names the item is reported as `file::item`.
    return [n if not item or file_names(n, item) else f"{n}::{item}" for n in names]


def file_names(name, item):
    """Whether some file `name` (as file_exists reads it) mentions `item`."""
    for f in source_files():
        if f == name or f.endswith("/" + name):
            if re.search(r"\b" + re.escape(item) + r"\b", (ROOT / f).read_text(encoding="utf-8")):
                return True
    return False


def module_exists(path):
    """A core module path (`input::orient::face_signs`): its modules are files under
    crates/primdecomp/src, and what follows the last one is named in it."""
    segs = path.split("::")
    if not ((CORE / segs[0]).is_dir() or (CORE / (segs[0] + ".rs")).exists()):
        return True  # another crate's path, or a type's member: not checked here
    here, k = CORE, 0
    while k < len(segs) and ((here / segs[k]).is_dir() or (here / (segs[k] + ".rs")).exists()):
        here, k = here / segs[k], k + 1
    files = [here.with_suffix(".rs")] if here.with_suffix(".rs").exists() else []
    if here.is_dir():
        files += sorted(here.rglob("*.rs"))
    text = "\n".join(p.read_text(encoding="utf-8") for p in files)
    return all(re.search(r"\b" + re.escape(s) + r"\b", text) for s in segs[k:])


def code_problems(path):
    """The files and core modules a record's `Code:` line names that no longer exist."""
    found = header(path)
    if found is None:
        return []
    code = re.split(r"\bwas\b", found[1][3])[0]
    problems = []
    for token in CODE_TOKEN.findall(code):
        if token.startswith("-") or "://" in token:
            continue
        if "/" in token or re.search(r"\.(rs|py|sh|toml|md|js)(::\w+)?$", token):
            ok = all(file_exists(name) for name in spelled_files(token))
        elif MODULE_PATH.match(token):
            ok = module_exists(token)
        else:
            continue
        if not ok:
            problems.append(f"{path.relative_to(ROOT)}: Code: names `{token}`, which does not exist")
    return problems


MODULES = ROOT / "docs" / "modules.md"


def modules_problems():
    """docs/modules.md against crates/primdecomp/src: every file named (itself, in a
    `dir/{a,b}.rs` form, or by its module's folder; `mod.rs`, `tests.rs` and `lib.rs` go with
    their folder), and every core path it names existing."""
    names = set()
    for token in CODE_TOKEN.findall(MODULES.read_text(encoding="utf-8")):
        m = re.match(r"^(.*)\{([^}]*)\}(.*)$", token)
        names.update([m[1] + part + m[3] for part in m[2].split(",")] if m else [token])
    have = {p.relative_to(CORE).as_posix() for p in CORE.rglob("*.rs")}
    problems = []
    for f in sorted(have):
        parts = f.split("/")
        # A module's own folder (`primitive/fit/`) stands for its files; a stage's
        # folder (`cut/`) does not.
        folders = ("/".join(parts[:k]) + "/" for k in range(2, len(parts)))
        if not (f in names or f == "lib.rs" or f.endswith(("/tests.rs", "/mod.rs"))
                or any(d in names for d in folders)):
            problems.append(f"docs/modules.md: does not name crates/primdecomp/src/{f}")
    tops = {p.name for p in CORE.iterdir()}
    for n in sorted(names):
        if n.split("/")[0] in tops and n.endswith((".rs", "/")) and not (CORE / n).exists():
            problems.append(f"docs/modules.md: names {n}, which crates/primdecomp/src lacks")
    return problems


def table(top):
    cell = lambda s: s.replace("|", "\\|")
    rows = []
    for p in top:
        title, (decision, status, *_) = header(p)
        rows.append(f"| [{cell(title)}]({p.name}) | {cell(decision)} | {cell(status)} |\n")
    return TABLE_HEAD + "".join(rows)


def public_names():
    """What lib.rs makes public at the crate root: every name of a `pub use` (its
    `as` name when renamed), every `pub fn`/`pub struct`/… defined there, and every
    `pub mod` as `name::`. Items under `#[cfg(feature = "test-internals")]` (the
    hidden `internals` module) are not part of the API."""
    text = re.sub(r"//[^\n]*", "", LIB.read_text(encoding="utf-8"))
    text = re.sub(r'#\[cfg\(feature = "test-internals"\)\]\s*(#\[[^\]]*\]\s*)*pub mod \w+ \{.*',
                  "", text, flags=re.S)
    names = set()
    for m in re.finditer(r"\bpub use\s+([^;]+);", text):
        body = m.group(1)
        inner = body[body.index("{") + 1:body.rindex("}")] if "{" in body else body.rsplit("::", 1)[-1]
        for item in re.split(r"\s*,\s*", inner.strip()):
            if item:
                names.add(item.split(" as ")[-1].strip().rsplit("::", 1)[-1])
    for m in re.finditer(r"\bpub (?:fn|struct|enum|trait|type|const|static)\s+(\w+)", text):
        names.add(m.group(1))
    for m in re.finditer(r"\bpub mod\s+(\w+)", text):
        names.add(m.group(1) + "::")
    return names


def api_table_problems():
    """ARCHITECTURE.md's API table against lib.rs: the second column lists the root
    names in backticks (paths such as `Mesh::from_triangles` are notes, not names); a
    row whose first column names a public module as `name::` describes what is
    inside it."""
    lines = ARCH.read_text(encoding="utf-8").splitlines()
    problems = []
    if len(lines) > ARCH_MAX_LINES:
        problems.append(f"ARCHITECTURE.md: {len(lines)} lines, more than the {ARCH_MAX_LINES} "
                        "a five-minute read holds")
    if API_HEADING not in lines:
        return problems + [f"ARCHITECTURE.md: no section {API_HEADING!r}"]
    table, i = [], lines.index(API_HEADING) + 1
    while i < len(lines) and not lines[i].startswith("|"):
        i += 1
    while i < len(lines) and lines[i].startswith("|"):
        table.append(lines[i])
        i += 1
    listed = set()
    for row in table[2:]:
        cells = [c.strip() for c in row.strip("|").split("|")]
        if len(cells) < 2:
            continue
        modules = [n for n in re.findall(r"`([^`]+)`", cells[0])
                   if n.endswith("::") and IDENT.match(n[:-2])]
        listed.update(modules)
        if modules:
            continue  # a public module's row names what is inside it
        for name in re.findall(r"`([^`]+)`", cells[1]):
            if IDENT.match(name):
                listed.add(name)
    public = public_names()
    for name in sorted(public - listed):
        problems.append(f"ARCHITECTURE.md: the API table does not list `{name}`, public in lib.rs")
    for name in sorted(listed - public):
        problems.append(f"ARCHITECTURE.md: the API table lists `{name}`, not public in lib.rs")
    return problems


def main():
    problems = api_table_problems() + modules_problems()
    for doc in documents():
        problems += link_problems(doc)
    top, steps = records()
    for p in top + steps:
        if header(p) is None:
            problems.append(f"{p.relative_to(ROOT)}: no five-line header ({', '.join(FIELDS)})")
        problems += code_problems(p)
    readme = DECISIONS / "README.md"
    text = readme.read_text(encoding="utf-8")
    start = text.find(TABLE_HEAD)
    if not problems or "--write" in sys.argv:
        if all(header(p) for p in top):
            want = table(top)
            if "--write" in sys.argv:
                body = text[:start] if start >= 0 else text.rstrip("\n") + "\n\n"
                readme.write_text(body + want, encoding="utf-8")
            elif start < 0 or text[start:] != want:
                problems.append("docs/decisions/README.md: the table does not match the records' "
                                "headers (run scripts/check_docs.py --write)")
    for p in problems:
        print(p)
    print(f"check_docs: {len(documents())} documents, {len(top) + len(steps)} records, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
