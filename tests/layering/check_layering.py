#!/usr/bin/env python3
"""Checks that every module includes only what its CMake target links (src/<module>/CMakeLists.txt).

The compiler already refuses another module's private headers (each module sees only its own
private folder and the internal interfaces it links). Public headers all sit under include/, so
the compiler cannot refuse those: here an include of module B's public header from module A passes
only if A links B, directly or through the modules it links. Prints each wrong-way include and
exits 1 if there is one.

Usage: check_layering.py [SOURCE_DIR]
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])

# The headers directly under include/vksplat/ are every module's vocabulary, owned by none:
# errors, the reference constants (glslang compiles them too), and render_types.hpp, which both
# renderers speak (the reference rasterizer uses its types, never RenderSettings::validate()).
TOP_LEVEL = {'render_types': None, 'constants': None, 'error': None}
# version.hpp (generated) is everyone's too. vksplat.h, the C API, sits beside them (what C
# programs include) but is capi's.
TOP_LEVEL.update({'version': None, 'vksplat.h': 'capi'})

modules = {}  # module -> (target, links: set of targets)
for cmake in sorted(root.glob('src/*/CMakeLists.txt')):
    text = re.sub(r'#.*', '', cmake.read_text())
    call = re.search(r'vksplat_(module|header_module)\(\s*(\w+)([^)]*)\)', text)
    if not call:
        continue
    name, words = call.group(2), call.group(3).split()
    target = words[words.index('TARGET') + 1] if 'TARGET' in words else f'vksplat_{name}'
    links = {w for w in words if w.startswith('vksplat_') and w != target}
    modules[name] = (target, links)
by_target = {target: name for name, (target, _) in modules.items()}


def module_of(target):
    return by_target.get(target[:-len('_internal')] if target.endswith('_internal') else target)


def reachable(name, seen=None):
    seen = set() if seen is None else seen
    for target in modules[name][1]:
        other = module_of(target)
        if other and other not in seen:
            seen.add(other)
            reachable(other, seen)
    return seen


# Modules of private headers only (stats): linking one is how a module may include it.
header_only = {n for n in modules if not list((root / 'src' / n).glob('*.cpp'))}
wrong = []
for name, (target, links) in modules.items():
    public_ok = reachable(name) | {name}
    private_ok = {name} | {module_of(t) for t in links if t.endswith('_internal')}
    private_ok |= {n for n in map(module_of, links) if n in header_only}
    if 'vksplat_shaders' in links:
        private_ok.add('shaders')
    files = list((root / 'src' / name).glob('*.[ch]pp')) + list((root / 'include/vksplat' / name).glob('*.hpp'))
    for path in files:
        for line_number, line in enumerate(path.read_text().splitlines(), 1):
            include = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not include:
                continue
            parts = include.group(1).split('/')
            if parts[0] == 'vksplat':
                owner = parts[1] if len(parts) > 2 else TOP_LEVEL.get(parts[1].removesuffix('.hpp'), '?')
                if owner is None or owner in public_ok:
                    continue
                why = 'an unknown public header' if owner == '?' else f'{modules[name][0]} does not link {owner}'
            elif len(parts) > 1:
                if parts[0] in private_ok:
                    continue
                why = f'private header of {parts[0]}, which {name} does not link as an internal interface'
            else:
                continue
            wrong.append(f'{path.relative_to(root)}:{line_number}: {include.group(1)}: {why}')

for line in wrong:
    print(line)
print(f'{len(modules)} modules, {len(wrong)} wrong-way includes')
sys.exit(1 if wrong else 0)
