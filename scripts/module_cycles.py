#!/usr/bin/env python3
"""Lists import cycles between the modules (files) of each crate under crates/.

A module is a file (`src/merge/driver.rs` is `merge::driver`, `mod.rs`/`lib.rs` are
their folder's module). An edge a -> b is any `crate::b...`, `super::...` or `self::`
path in a's code outside `#[cfg(test)]` blocks that names b or an item of b; a parent
module re-exporting its children (`pub use child::X`, `mod child`) is not an edge.
Prints each strongly connected component of two or more modules and exits 1 if
there is any, so CI keeps the graph acyclic.

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

def edges(mods, mod, text):
    text = re.sub(r'//[^\n]*', '', strip_tests(text))
    out = set()
    # `use a::{b, c::d}`: expand one level of braces.
    for m in re.finditer(r'\buse\s+(crate|super|self)((?:::\w+)*)::\{([^}]*)\}', text):
        for part in m.group(3).split(','):
            part = part.strip().split(' as ')[0].strip()
            if part and part != 'self':
                text += f'\n{m.group(1)}{m.group(2)}::{part};'
    for m in PATH.finditer(text):
        head, rest = m.group(1), [s for s in m.group(2).split('::') if s]
        if head == 'crate':
            base = []
        elif head == 'super':
            base = list(mod[:-1])
            while rest and rest[0] == 'super':
                base, rest = base[:-1], rest[1:]
        else:
            base = list(mod)
        target = resolve(mods, mod, base + rest)
        if target is None or target == mod:
            continue
        # A parent naming its own child (re-exports) is not a dependency cycle edge.
        if target[:len(mod)] == mod:
            continue
        out.add(target)
    return out

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

def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
    dirs = sys.argv[1:] or sorted(
        os.path.join(root, 'crates', c, 'src') for c in os.listdir(os.path.join(root, 'crates')))
    bad = 0
    for src in dirs:
        mods = modules(src)
        graph = {m: edges(mods, m, open(p).read()) for m, p in mods.items()}
        for comp in sccs(graph):
            if len(comp) > 1:
                bad += 1
                names = sorted('::'.join(c) or 'crate' for c in comp)
                print(f'{os.path.relpath(src, root)}: cycle among {", ".join(names)}')
                for a in sorted(comp):
                    for b in sorted(graph[a] & set(comp)):
                        print(f'    {"::".join(a) or "crate"} -> {"::".join(b) or "crate"}')
    print('no import cycles' if not bad else f'{bad} cycle(s)')
    sys.exit(1 if bad else 0)

main()
