#!/usr/bin/env python3
"""Every file, folder, module and item that ARCHITECTURE.md, the README,
the guide (src/guide/) and the comments of the workspace's Rust files name
in backticks exists.

What it checks, by the shape of what stands in backticks:
  - a path (`runtime/src/step/events.rs`, `tests/ui/*.rs`, `emit/`): a
    file or folder of the repository, read from the repository's root,
    from the naming file's folder or crate, or as the end of a tracked
    path (`step/events.rs`); globs match at least one file;
  - a Rust path (`crate::dae::reduce`, `Method::Radau5`,
    `daegen_runtime::instants`): each of its segments is the name of a
    module, file, item, variant or field defined in the workspace;
  - an item's name of two or more words in CamelCase (`BlockSolution`):
    a type, trait, variant or constant defined in the workspace, unless
    `.ci/foreign-names` lists it as another project's (FMI's, Modelica's,
    a peer's).

Prints one line per name that does not exist (file:line: `name`) and a
last line with the count; exits 1 where there is any.

    python3 .ci/named-things-exist.py    # from the workspace root"""
import fnmatch, os, re, subprocess, sys

ROOT = os.getcwd()


def tracked():
    out = subprocess.run(['git', 'ls-files', '--cached', '--others', '--exclude-standard'],
                         capture_output=True, text=True, check=True).stdout
    return [p for p in out.splitlines() if os.path.exists(p)]


FILES = tracked()
DIRS = {os.path.dirname(p) for p in FILES}
for d in list(DIRS):
    while d:
        DIRS.add(d)
        d = os.path.dirname(d)

# Names defined in the workspace's Rust code: items, variants, fields,
# modules (files and folders), crates.
DEFINED = set()
ITEM = re.compile(r'\b(?:fn|struct|enum|trait|mod|type|const|static|union|macro_rules!)\s+(r#)?([A-Za-z_]\w*)')
VARIANT_OR_FIELD = re.compile(r'^\s*(?:pub(?:\([^)]*\))?\s+)?([A-Za-z_]\w*)\s*(?:[:({,]|$)', re.M)
for path in FILES:
    if path.endswith('.rs'):
        text = open(path, encoding='utf-8').read()
        DEFINED.update(m.group(2) for m in ITEM.finditer(text))
        DEFINED.update(m.group(1) for m in VARIANT_OR_FIELD.finditer(text))
        DEFINED.update(re.findall(r'#\[macro_export\]\s*macro_rules!\s*(\w+)', text))
        stem = os.path.basename(path)[:-3]
        DEFINED.add(stem)
        # The types `#[dae_model] fn van_der_pol()` generates.
        for fn in re.findall(r'\bfn\s+([a-z_][a-z0-9_]*)', text):
            camel = ''.join(w[:1].upper() + w[1:] for w in fn.split('_'))
            DEFINED.update({camel, camel + 'Sensitivities', camel + 'Batch'})
        DEFINED.update(os.path.dirname(path).split('/'))
    if os.path.basename(path) == 'Cargo.toml':
        for name in re.findall(r'^name\s*=\s*"([^"]+)"', open(path).read(), re.M):
            DEFINED.update({name, name.replace('-', '_')})
DEFINED.update({'crate', 'self', 'super', 'std', 'core', 'alloc', 'proc_macro', 'proc_macro2',
                'syn', 'quote', 'nalgebra', 'insta', 'serde', 'rayon', 'plotters', 'libloading',
                'trybuild', 'serde_json', 'roxmltree', 'proptest', 'diffsol', 'ode_solvers',
                'sundials_sys', 'prettyplease', 'Self'})

FOREIGN = set()
foreign_file = os.path.join('.ci', 'foreign-names')
if os.path.exists(foreign_file):
    for line in open(foreign_file):
        line = line.split('#')[0].strip()
        if line:
            FOREIGN.add(line)

PATH_LIKE = re.compile(r'^[\w.*-]+(/[\w.*-]*)+$|^[\w*-]+\.(rs|md|py|toml|sh|dae|urdf|json|csv|svg|stderr)$')
RUST_PATH = re.compile(r'^(?:[A-Za-z_]\w*::)+[A-Za-z_]\w*(?:!|\(\))?$')
CAMEL = re.compile(r'^[A-Z][a-z0-9]+(?:[A-Z][a-z0-9]+)+$')


def is_path(name):
    """Whether `name` reads as a path of the repository: with an extension,
    a trailing slash, or a first segment that is one of its folders (not
    a fraction, `1/2`, or a ratio of names, `num/den`)."""
    if not PATH_LIKE.match(name) or '://' in name:
        return False
    if name.startswith(('target/', '../', 'shared/')):
        # Built, or outside the repository: not there to check.
        return False
    first = name.split('/')[0]
    return (name.endswith('/') or '.' in name.split('/')[-1]
            or any(d == first or d.endswith('/' + first) for d in DIRS))


def path_exists(name, naming_file):
    name = name.rstrip('/')
    bases = ['', os.path.dirname(naming_file)]
    crate = naming_file.split('/')[0]
    bases += [crate, crate + '/src']
    for base in bases:
        candidate = os.path.normpath(os.path.join(base, name))
        if any(ch in candidate for ch in '*?['):
            if any(fnmatch.fnmatch(p, candidate) for p in FILES):
                return True
        elif candidate in DIRS or candidate in FILES or candidate + '.rs' in FILES:
            return True
    # The end of a tracked path: `step/events.rs`, `emit/`.
    suffix = '/' + name
    ends = [suffix, suffix + '.rs']
    if any(('/' + p).endswith(e) for p in FILES for e in ends):
        return True
    if any(('/' + d).endswith(suffix) for d in DIRS):
        return True
    return False


# The standard library's and the language's own: not ours to check.
STD_FIRST = {'std', 'core', 'alloc', 'f64', 'f32', 'usize', 'isize', 'u8', 'u16', 'u32', 'u64',
             'i8', 'i16', 'i32', 'i64', 'bool', 'char', 'str', 'String', 'Vec', 'Option',
             'Result', 'Box', 'Rc', 'Arc', 'HashMap', 'HashSet', 'BTreeMap', 'Iterator'}


def check(name, naming_file):
    if name in FOREIGN:
        return True
    if is_path(name):
        return path_exists(name, naming_file)
    if PATH_LIKE.match(name):
        return True
    if RUST_PATH.match(name):
        segments = name.rstrip('!').removesuffix('()').split('::')
        if segments[0] in STD_FIRST:
            return True
        return all(s in DEFINED or s in FOREIGN for s in segments)
    if CAMEL.match(name):
        return name in DEFINED or name in STD_FIRST
    return True


TICKED = re.compile(r'`([^`\n]+)`')
COMMENT = re.compile(r'^\s*//[/!]?(.*)$')


def named(path):
    """(line, name) of every backticked name the file's prose holds."""
    lines = open(path, encoding='utf-8').read().split('\n')
    in_code = False
    for k, line in enumerate(lines, 1):
        if path.endswith('.rs'):
            m = COMMENT.match(line)
            if not m:
                continue
            line = m.group(1)
        if line.strip().startswith('```'):
            in_code = not in_code
            continue
        if in_code:
            continue
        for t in TICKED.finditer(line):
            yield k, t.group(1).strip()


def documents():
    for p in FILES:
        if p in ('ARCHITECTURE.md', 'README.md') or p.startswith('src/guide/'):
            yield p
        elif p.endswith('.rs') and not p.startswith(('bench/', 'fuzz/')):
            yield p
        elif p.endswith('.rs') and p.startswith('bench/src/'):
            yield p


def defined_under(folder):
    """The files, folders and item names under each folder ending in
    `folder` (`linalg/` is runtime/src/linalg)."""
    names = set()
    roots = [d for d in DIRS if d == folder or d.endswith('/' + folder)]
    for p in FILES:
        if not any(p.startswith(r + '/') for r in roots):
            continue
        for r in roots:
            if p.startswith(r + '/'):
                rest = p[len(r) + 1:].split('/')
                names.update(part.removesuffix('.rs') for part in rest)
        if p.endswith('.rs'):
            names.update(m.group(2) for m in ITEM.finditer(open(p, encoding='utf-8').read()))
    return names


def table_rows(path):
    """(line, name) of the lowercase names a row of ARCHITECTURE.md's
    tables gives for the one folder its first cell names, all but those of
    the last column when it is the one that says what the folder reads:
    each must be a file, folder or item under that folder."""
    reads_last = False
    for k, line in enumerate(open(path, encoding='utf-8').read().split('\n'), 1):
        if line.startswith('| ') and not line.startswith('| `'):
            reads_last = line.rstrip(' |').endswith('reads')
        if not line.startswith('| `'):
            continue
        cells = line.strip().strip('|').split('|')
        folders = [f.rstrip('/') for f in TICKED.findall(cells[0]) if f.endswith('/')]
        if len(folders) != 1:
            continue
        described = cells[1:-1] if reads_last else cells[1:]
        under = defined_under(folders[0])
        for t in TICKED.finditer('|'.join(described)):
            name = t.group(1)
            if re.match(r'^[a-z_][a-z0-9_]*$', name) and name not in under:
                yield k, f'{name}` under `{folders[0]}/'


missing = []
for line, name in table_rows('ARCHITECTURE.md'):
    missing.append(f'ARCHITECTURE.md:{line}: `{name}`')
for doc in documents():
    for line, name in named(doc):
        if not check(name, doc):
            missing.append(f'{doc}:{line}: `{name}`')
for m in missing:
    print(m)
print(f'{len(missing)} names that do not exist')
sys.exit(1 if missing else 0)
