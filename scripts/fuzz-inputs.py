#!/usr/bin/env python3
"""Mutation fuzzing of reamsim-cli's inputs: mesh files (every format, text and binary) and plan files.

    scripts/fuzz-inputs.py OUT_DIR [SECONDS] [--workers N] [--cli PATH]

Seeds: a 10 mm cube written by `reamsim-cli export` in STL (binary and ASCII), OBJ, PLY (binary and ASCII),
OFF and VTP, and resources/plans/default_plan.json. Each case mutates one seed (a number token replaced by
nan, inf, -1, 1e400, 65536, 4294967295, ...; bytes flipped, inserted, repeated, cut short) and runs
`info FILE --json` or `export FILE --out ... --repair` (meshes) or `ream --bone default --plan FILE` (plans).
A case is kept in OUT_DIR/found/ when the program dies of a signal, fails without saying why on stderr, or
runs past the time limit (20 s for meshes, 60 s for plans); a summary line per worker goes to stdout.
Session 46 found with it that `export --repair` of a box with one vertex moved 65 m away ran for hours
(the volumetric remesh's band, now limited: modules/mesh/src/repair/VolumetricRemesh.cpp).
Needs the Release build (scripts/build.sh). Not part of test.sh: it runs as long as it is asked to. The
readers alone, under AddressSanitizer and with every format's header mutated, are scripts/fuzz-readers.sh.
"""
import argparse
import os
import random
import re
import subprocess
import sys
import time
from multiprocessing import Process

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CUBE_OBJ = """v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8
"""
TOKENS = [b'nan', b'NaN', b'inf', b'-inf', b'Infinity', b'-1', b'1e400', b'65536', b'4294967295', b'2147483648',
          b'99999999999', b'0', b'-0', b'1e-400', b'', b'3', b'255', b'1e308', b'-2147483649', b'1e9', b'null',
          b'"x"', b'[]', b'{}']
NUMBER = re.compile(rb'-?\d+(\.\d+)?([eE]-?\d+)?')


def make_seeds(cli, seed_dir):
    os.makedirs(seed_dir, exist_ok=True)
    cube = os.path.join(seed_dir, 'cube.obj')
    with open(cube, 'w') as f:
        f.write(CUBE_OBJ)
    seeds = [cube]
    for name, extra in [('b.stl', []), ('a.stl', ['--ascii']), ('b.ply', []), ('a.ply', ['--ascii']),
                        ('c.off', []), ('c.vtp', [])]:
        out = os.path.join(seed_dir, name)
        subprocess.run([cli, 'export', cube, '--out', out] + extra, check=True, capture_output=True)
        seeds.append(out)
    return seeds


def mutate(rng, data, text):
    d = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        r = rng.random()
        numbers = list(NUMBER.finditer(bytes(d))) if text and r < 0.5 else []
        if numbers:
            m = rng.choice(numbers)
            d[m.start():m.end()] = rng.choice(TOKENS)
        elif r < 0.65 and d:
            d[rng.randrange(len(d))] = rng.randrange(256)
        elif r < 0.75 and d:
            i = rng.randrange(len(d))
            d[i:i + 4] = rng.choice([b'\xff\xff\xff\x7f', b'\x00\x00\x00\x80', b'\x00\x00\xc0\x7f', b'\xff\xff\xff\xff'])
        elif r < 0.85:
            d = d[:rng.randrange(len(d) + 1)]
        elif d:
            i = rng.randrange(len(d))
            d[i:i] = d[i:min(len(d), i + rng.randrange(1, 64))] * rng.randint(1, 5)
    return bytes(d)


def worker(index, args, seeds, plan_seed, found):
    rng = random.Random(1000 * index + int(time.time()))
    scratch = os.path.join(args.out, f'work{index}')
    os.makedirs(scratch, exist_ok=True)
    end = time.time() + args.seconds
    runs = kept = 0
    while time.time() < end:
        plan = rng.random() < 0.2
        seed = plan_seed if plan else rng.choice(seeds)
        ext = os.path.splitext(seed)[1]
        text = plan or ext in ('.obj', '.off') or os.path.basename(seed).startswith('a.')
        with open(seed, 'rb') as f:
            case = mutate(rng, f.read(), text)
        path = os.path.join(scratch, 'case' + ext)
        with open(path, 'wb') as f:
            f.write(case)
        if plan:
            cmd, limit = [args.cli, 'ream', '--bone', 'default', '--plan', path, '--out', os.path.join(scratch, 'ream')], 60
        elif rng.random() < 0.7:
            cmd, limit = [args.cli, 'info', path, '--json'], 20
        else:
            cmd, limit = [args.cli, 'export', path, '--out', os.path.join(scratch, 'out.stl'), '--repair'], 20
        why = None
        try:
            p = subprocess.run(cmd, capture_output=True, timeout=limit)
            if p.returncode < 0 or p.returncode >= 128:
                why = f'signal or abort (exit {p.returncode})'
            elif p.returncode != 0 and not p.stderr.strip():
                why = f'exit {p.returncode} without a message'
        except subprocess.TimeoutExpired:
            why = f'over {limit} s'
        runs += 1
        if why:
            kept += 1
            name = os.path.join(found, f'w{index}_{runs}{ext}')
            with open(name, 'wb') as f:
                f.write(case)
            print(f'found: {name}: {cmd[1]}: {why}', flush=True)
    print(f'worker {index}: {runs} cases, {kept} kept', flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('out')
    ap.add_argument('seconds', nargs='?', type=float, default=600)
    ap.add_argument('--workers', type=int, default=2)
    ap.add_argument('--cli', default=os.environ.get('REAMSIM_CLI', os.path.join(ROOT, 'build/app/cli/reamsim-cli')))
    args = ap.parse_args()
    if not os.access(args.cli, os.X_OK):
        sys.exit(f'fuzz-inputs: {args.cli} not found: build it (scripts/build.sh) or pass --cli')
    found = os.path.join(args.out, 'found')
    os.makedirs(found, exist_ok=True)
    seeds = make_seeds(args.cli, os.path.join(args.out, 'seeds'))
    plan_seed = os.path.join(ROOT, 'resources/plans/default_plan.json')
    procs = [Process(target=worker, args=(i, args, seeds, plan_seed, found)) for i in range(args.workers)]
    for p in procs:
        p.start()
    for p in procs:
        p.join()


if __name__ == '__main__':
    main()
