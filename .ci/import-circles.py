#!/usr/bin/env python3
"""Import circles of each Rust crate under the current folder: between its files,
and between its top-level modules (the folders and files directly under src/).

A file imports another when it names `crate::a::b` (or `super::`/`self::` paths
resolved from its own module) and `a::b` is defined by that file. Prints one
line per circle (files or modules joined by ' <-> ') and a last line with the
count of both; exits 1 where there is any circle but those allowed by name
in `.ci/allowed-circles` (one per line, as printed), where the types are
truly mutual (see ARCHITECTURE.md).

    python3 .ci/import-circles.py    # from the workspace root"""
import os, re, sys

def crate_roots():
    for dirpath, dirnames, files in os.walk('.'):
        dirnames[:] = [d for d in dirnames if d not in ('target', '.git', 'fuzz')]
        if 'Cargo.toml' in files and os.path.isdir(os.path.join(dirpath, 'src')):
            yield os.path.join(dirpath, 'src')

def module_of(src, path):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[-1] in ('lib', 'main', 'mod'):
        rel = rel[:-1]
    return tuple(rel)

PATH = re.compile(r'\b(crate|super|self)((?:::\w+)+)')
USE_GROUP = re.compile(r'use\s+(crate|super|self)((?:::\w+)*)::\{([^}]*)\}', re.S)

def scc(graph):
    index, low, stack, on, out, i = {}, {}, [], set(), [], [0]
    sys.setrecursionlimit(10000)
    def visit(v):
        index[v] = low[v] = i[0]; i[0] += 1; stack.append(v); on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v: break
            if len(comp) > 1: out.append(sorted(comp))
    for v in list(graph):
        if v not in index: visit(v)
    return out

total, modules = [], []
for src in crate_roots():
    files = {}
    for dp, _, fs in os.walk(src):
        for f in fs:
            if f.endswith('.rs'):
                p = os.path.join(dp, f)
                files[module_of(src, p)] = p
    graph = {p: set() for p in files.values()}
    for mod, p in files.items():
        text = open(p, encoding='utf-8', errors='replace').read()
        text = re.sub(r'#\[cfg\(test\)\]\s*mod tests\s*\{.*', '', text, flags=re.S)
        refs = [(m.group(1), m.group(2)) for m in PATH.finditer(text)]
        for m in USE_GROUP.finditer(text):
            for item in m.group(3).split(','):
                item = item.strip().split(' as ')[0].strip()
                if item and item != 'self':
                    refs.append((m.group(1), m.group(2) + '::' + item.replace('::{', '::').split('{')[0]))
        for root, tail in refs:
            parts = [x for x in tail.split('::') if x]
            if root == 'crate':
                start = ()
            elif root == 'super':
                start = mod[:-1]
                while parts and parts[0] == 'super':
                    start, parts = start[:-1], parts[1:]
            else:
                start = mod
            full = tuple(start) + tuple(parts)
            for k in range(len(full), 0, -1):
                tgt = files.get(full[:k])
                if tgt:
                    if tgt != p and k > 0 and full[:k] != ():
                        graph[p].add(tgt)
                    break
    for comp in scc(graph):
        total.append(comp)
        print(' <-> '.join(os.path.normpath(c) for c in comp))
    # The same graph between top-level modules (src/a.rs and src/a/ are one).
    top = lambda p: os.path.relpath(p, src).split(os.sep)[0].removesuffix('.rs')
    roots = {'lib', 'main', 'mod'}
    mgraph = {}
    for p, targets in graph.items():
        a = top(p)
        if a in roots: continue
        for t in targets:
            b = top(t)
            if b != a and b not in roots:
                mgraph.setdefault(a, set()).add(b); mgraph.setdefault(b, set())
    for comp in scc(mgraph):
        modules.append((os.path.normpath(src), comp))
        print('modules of ' + os.path.normpath(src) + ': ' + ' <-> '.join(comp))
print(f"{len(total)} import circles between files ({sum(len(c) for c in total)} files in them), {len(modules)} between modules")
allowed_path = os.path.join(os.path.dirname(__file__), 'allowed-circles')
allowed = set()
if os.path.exists(allowed_path):
    allowed = {l.strip() for l in open(allowed_path) if l.strip() and not l.startswith('#')}
printed = [' <-> '.join(os.path.normpath(c) for c in comp) for comp in total]
printed += ['modules of ' + src_name + ': ' + ' <-> '.join(comp) for src_name, comp in modules]
unexpected = [c for c in printed if c not in allowed]
for c in unexpected:
    print('not allowed: ' + c)
sys.exit(1 if unexpected else 0)
