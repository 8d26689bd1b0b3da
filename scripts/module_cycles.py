#!/usr/bin/env python3
"""Checks the import graph between the modules (files) of each crate under crates/.

A module is a file (`src/merge/driver.rs` is `merge::driver`, `mod.rs`/`lib.rs` are
their folder's module). An edge a -> b is any `crate::b...`, `super::...` or `self::`
path in a's code outside `#[cfg(test)]` blocks that names b or an item of b; a parent
module re-exporting its children (`pub use child::X`, `mod child`) is not an edge.

It lists, and exits 1 if there is any:
- cycles: each strongly connected component of two or more modules, in every crate;
- imports through the crate root: a path `crate::Name` (or `super::Name` reaching the
  root) where `Name` is a re-export of the root, not a module or an item the root
  defines; test code included. A name is imported from its home (`crate::primitive::
  Primitive`, not `crate::Primitive`), so the graph shows who really depends on whom;
- back-stage imports, in the crates of LAYERS: a stage's module importing from a later
  stage (the core's order is input -> seed -> merge -> cut -> postprocess -> output),
  a foundation (math, primitive) importing from a stage, or either importing from a
  driver at the top (decompose, ...). Top-level modules may import anything;
  ALLOWED lists the exceptions, each with its reason.

Usage: scripts/module_cycles.py [CRATE_DIR...] (default: every crates/*/src)."""
import os, re, sys

def modules(src):
    mods = {}
    for root, _, files in os.walk(src):
        for f in files:
            if not f.endswith('.rs'):
                continue
            path = os.path.join(root, f)
            rel = os.path.relpath(path, src)[:-3].split(os.sep)
            if rel[-1] in ('mod', 'lib', 'main'):
                rel = rel[:-1]
            mods[tuple(rel)] = path
    return mods

def strip_tests(text):
    """Drops `#[cfg(test)]` items (a `mod tests { ... }` or one fn) by brace matching."""
    out, i = [], 0
    while True:
        j = text.find('#[cfg(test)]', i)
        if j < 0:
            out.append(text[i:])
            return ''.join(out)
        out.append(text[i:j])
        k = text.find('{', j)
        semi = text.find(';', j)
        if semi >= 0 and (k < 0 or semi < k):
            i = semi + 1
            continue
        depth, p = 0, k
        while p < len(text):
            if text[p] == '{':
                depth += 1
            elif text[p] == '}':
                depth -= 1
                if depth == 0:
                    break
            p += 1
        i = p + 1

def resolve(mods, here, path):
    """The longest module prefix of an absolute path (tuple of segments)."""
    for n in range(len(path), 0, -1):
        if tuple(path[:n]) in mods:
            return tuple(path[:n])
    return None

PATH = re.compile(r'\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)')

def split_top(s):
    """Splits a use tree's list at its top-level commas."""
    parts, depth, cur = [], 0, ''
    for ch in s:
        if ch == ',' and depth == 0:
            parts.append(cur); cur = ''
            continue
        depth += (ch == '{') - (ch == '}')
        cur += ch
    return parts + [cur]

def expand(tree, prefix, out):
    """`a::{b, c::{d as e}}` -> a::b, a::c::d (into `out`)."""
    tree = tree.strip()
    i = tree.find('{')
    if i < 0:
        path = re.sub(r'::self$', '', prefix + tree.split(' as ')[0].strip())
        if path and path != 'self':
            out.append(path)
        return
    inner = tree[i + 1:tree.rindex('}')]
    for part in split_top(inner):
        if part.strip():
            expand(part, prefix + tree[:i], out)

def paths(text):
    """Every `crate::`, `super::` and `self::` path in `text`, `use` trees expanded,
    as (head, [segments])."""
    used = []
    def take(m):
        expand(' '.join(m.group(1).split()), '', used)
        return ';'
    rest = re.sub(r'\buse\s+([^;]*);', take, text)
    found = [(m.group(1), m.group(2)) for m in PATH.finditer(rest)]
    for u in used:
        m = re.match(r'(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)', u)
        if m:
            found.append((m.group(1), m.group(2)))
    return [(h, [s for s in r.split('::') if s]) for h, r in found]

def absolute(mod, head, rest):
    """The path's segments from the crate root."""
    if head == 'crate':
        return rest
    if head == 'super':
        base = list(mod[:-1])
        while rest and rest[0] == 'super':
            base, rest = base[:-1], rest[1:]
        return base + rest
    return list(mod) + rest

def code(text):
    return re.sub(r'//[^\n]*', '', text)

def blocks(text, sub=()):
    """A file's code by inline module, as [(path below the file's module, text)]: each
    `mod x { ... }` cut out of its parent's text, so `super::` resolves from where it
    is written."""
    res, parts, i = [], [], 0
    pat = re.compile(r'\bmod\s+(\w+)\s*\{')
    while True:
        m = pat.search(text, i)
        if not m:
            parts.append(text[i:])
            break
        parts.append(text[i:m.start()])
        depth, p = 0, m.end() - 1
        while p < len(text):
            depth += (text[p] == '{') - (text[p] == '}')
            if depth == 0:
                break
            p += 1
        res += blocks(text[m.end():p], sub + (m.group(1),))
        i = p + 1
    return [(sub, ''.join(parts))] + res

def module_paths(mod, text):
    """Every path of `text` (the code of file module `mod`) from the crate root, as
    (head, segments as written, absolute segments)."""
    return [(h, r, absolute(mod + sub, h, r))
            for sub, part in blocks(code(text)) for h, r in paths(part)]

def test_only(mods, texts):
    """File modules compiled only for tests (`#[cfg(test)] mod x;` in their parent)."""
    out = set()
    for m in mods:
        if m and re.search(r'#\[cfg\(test\)\]\s*(pub(\([^)]*\))?\s+)?mod\s+' + m[-1] + r'\s*;',
                           texts.get(m[:-1], '')):
            out.add(m)
    return out

def edges(mods, mod, text):
    out = set()
    for head, rest, segs in module_paths(mod, strip_tests(text)):
        target = resolve(mods, mod, segs)
        if target is None or target == mod:
            continue
        # A parent naming its own child (re-exports) is not a dependency cycle edge.
        if target[:len(mod)] == mod:
            continue
        out.add(target)
    return out

ROOT_ITEM = re.compile(
    r'\b(?:fn|struct|enum|const|static|type|trait|union|mod|macro_rules!)\s+([A-Za-z_]\w*)')

EXTERN_ALIAS = re.compile(r'^\s*use\s+\w+\s+as\s+(\w+)\s*;', re.M)


def through_root(mods, mod, text, own):
    """The paths of `mod` that name a re-export of the crate root (`crate::Primitive`):
    `crate::` paths anywhere (tests too), `super::` ones outside tests."""
    found = set()
    candidates = [p for p in module_paths(mod, text) if p[0] == 'crate']
    candidates += [p for p in module_paths(mod, strip_tests(text)) if p[0] == 'super']
    for head, rest, segs in candidates:
        if segs and (segs[0],) not in mods and segs[0] not in own and segs[0] not in (
                'self', 'super', 'crate'):
            found.add(f'{head}::' + '::'.join(rest))
    return sorted(found)

# The crates whose folders are ordered, by crate folder name. A module is placed by the
# first segment of its path: `stages` in pipeline order (`aliases` name the same stage
# under another folder name), `foundations` (which any stage may use, in their own
# order), `shared` top-level definitions (settings, errors, progress, results) that any
# module may use; any other top-level module is a driver, which may import anything and
# which no stage or foundation imports.
LAYERS = {
    'primdecomp': {
        'stages': ['input', 'seed', 'merge', 'cut', 'postprocess', 'output'],
        'aliases': {'export': 'output'},
        'foundations': ['math', 'primitive'],
        # output::result: the result types (Decomposition, Level, Shortfall) every
        # stage fills its part of; they live with the output that writes them.
        'shared': ['error', 'params', 'progress', 'result', 'output::result'],
    },
}

# (crate, importing module, imported module) -> why this import may break the order.
ALLOWED = {
    ('primdecomp', 'cut::error', 'output'):
        "a cut node's distance is measured over its primitive's conservative tessellation, "
        "which today lives with the OBJ writer (output/obj.rs); it belongs with the primitives",
    ('primdecomp', 'cut::chamfer', 'output'):
        "a level's mean distance is measured over the same tessellation as cut::error's",
    ('primdecomp', 'output::json', 'decompose::objects'):
        "the JSON contract writes a per-object run's settings (Objects, "
        "SHARE_RULE), which the per-object entry defines beside the run",
}

def place(layers, mod):
    """(kind, rank) of a module: kind in stage, foundation, shared, driver."""
    if not mod:
        return ('driver', 0)
    if any('::'.join(mod[:len(s.split('::'))]) == s for s in layers['shared']):
        return ('shared', 0)
    top = layers['aliases'].get(mod[0], mod[0])
    if top in layers['stages']:
        return ('stage', layers['stages'].index(top))
    if top in layers['foundations']:
        return ('foundation', layers['foundations'].index(top))
    if top in layers['shared']:
        return ('shared', 0)
    return ('driver', 0)

def back_stage(layers, a, b):
    """Why the edge a -> b runs against the order, or None."""
    (ka, ra), (kb, rb) = place(layers, a), place(layers, b)
    if ka in ('shared', 'driver') or kb == 'shared':
        return None
    if kb == 'driver':
        return f'a {ka} imports the driver {"::".join(b)}'
    if ka == 'stage' and kb == 'stage' and rb > ra:
        return 'an earlier stage imports a later one'
    if ka == 'foundation' and kb == 'stage':
        return 'a foundation imports a stage'
    if ka == 'foundation' and kb == 'foundation' and rb > ra:
        return 'a foundation imports a later foundation'
    return None

def sccs(graph):
    index, low, stack, on, res, n = {}, {}, [], set(), [], [0]
    def visit(v):
        index[v] = low[v] = n[0]; n[0] += 1
        stack.append(v); on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v:
                    break
            res.append(comp)
    sys.setrecursionlimit(10000)
    for v in graph:
        if v not in index:
            visit(v)
    return res

def name(m):
    return '::'.join(m) or 'crate'

def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
    dirs = sys.argv[1:] or sorted(
        os.path.join(root, 'crates', c, 'src') for c in os.listdir(os.path.join(root, 'crates')))
    cycles = roots = backs = 0
    used = set()
    for src in dirs:
        where = os.path.relpath(src, root)
        crate = os.path.basename(os.path.dirname(os.path.abspath(src)))
        mods = modules(src)
        texts = {m: open(p).read() for m, p in mods.items()}
        tests = test_only(mods, texts)
        graph = {m: edges(mods, m, texts[m]) if m not in tests else set() for m in mods}
        for comp in sccs(graph):
            if len(comp) > 1:
                cycles += 1
                print(f'{where}: cycle among {", ".join(sorted(name(c) for c in comp))}')
                for a in sorted(comp):
                    for b in sorted(graph[a] & set(comp)):
                        print(f'    {name(a)} -> {name(b)}')
        own = set(ROOT_ITEM.findall(code(texts.get((), ''))))
        # `use other_crate as name;` at the root: `crate::name::…` is the other crate
        # itself (its home), not a re-export of this one.
        own |= set(EXTERN_ALIAS.findall(code(texts.get((), ''))))
        for m in sorted(mods):
            if not m:
                continue
            for path in through_root(mods, m, texts[m], own):
                roots += 1
                print(f'{where}: {name(m)} imports {path} through the crate root')
        layers = LAYERS.get(crate)
        if layers:
            for a in sorted(graph):
                for b in sorted(graph[a]):
                    why = back_stage(layers, a, b)
                    if why and (crate, name(a), name(b)) in ALLOWED:
                        used.add((crate, name(a), name(b)))
                    elif why:
                        backs += 1
                        print(f'{where}: {name(a)} -> {name(b)}: {why}')
    for key in sorted(set(ALLOWED) - used):
        if not sys.argv[1:]:
            print(f'note: the exception {key} is no longer needed: remove it from ALLOWED')
    print(f'{cycles} import cycle(s), {roots} import(s) through the crate root, '
          f'{backs} back-stage import(s)')
    sys.exit(1 if cycles or roots or backs else 0)

main()
