#!/usr/bin/env python3
"""Mutation fuzzer for ReamSim's file readers (driver: tests/fuzz/reader_fuzz_driver.cpp).

Writes N mutants of every seed, runs the driver on them in batches (one process per batch, a timeout per
input inside the driver) and keeps every input that crashes the driver, hangs it, makes a sanitizer report,
gives a FINDING line, or gets an error message that does not name the file. One copy per distinct signature
goes to --out with a .log beside it; messages.tsv there counts the error messages (paths and numbers
blanked) so that unclear ones can be read through.

Modes: mesh, plan, presets, volume (seed files in the --seeds directories; the other files of a seed's
directory - detached data, slice files - are linked beside the mutants) and dicom (every directory of .dcm
files under --seeds is a series; a mutant is a copy of the series with one file mutated, read through the
directory or through that file). Mutations favour headers: the first bytes of a NIfTI file, a DICOM file up
to its pixel data, the uncompressed content of a .gz file.

  scripts/fuzz-readers.py --driver build-asan/tests/fuzz/reader_fuzz_driver --mode volume \\
      --seeds /tmp/seeds/volume --out /tmp/fuzz-out --mutations 500
"""
import argparse
import collections
import gzip
import hashlib
import itertools
import os
import random
import re
import shutil
import signal
import struct
import subprocess
import sys
import time

EXTENSIONS = {
    'mesh': ('.stl', '.obj', '.ply', '.off', '.vtp'),
    'plan': ('.json',),
    'presets': ('.json',),
    'landmarks': ('.json',),
    'volume': ('.nii', '.nii.gz', '.nrrd', '.nhdr', '.mha', '.mhd'),
}
DRIVER_MODE = {'dicom': 'volume'}

INTS = [0, -1, 1, 2, 3, 7, 255, 256, 32767, 32768, 65535, 65536, 2**31 - 1, 2**31, -2**31, 2**32 - 1,
        2**63 - 1, -2**63, 10**9]
FLOATS = [float('nan'), float('inf'), -float('inf'), 0.0, -0.0, 1e-45, 1e-300, 1e30, 1e308, -1e308, 3.5e38, -1.0, 0.5]
TEXT_NUMBERS = [b'0', b'-1', b'1', b'2', b'65535', b'65536', b'2147483647', b'2147483648', b'-2147483648',
                b'4294967296', b'9223372036854775808', b'99999999999999999999', b'nan', b'inf', b'-inf', b'1e308',
                b'1e309', b'1e-320', b'-0', b'0x10', b'1.5e', b'.', b'-', b'1' * 400]
WORDS = {
    'mesh': [b'solid', b'endsolid', b'facet', b'vertex', b'endloop', b'v', b'f', b'OFF', b'COFF', b'ply',
             b'format', b'binary_little_endian', b'element', b'property', b'list', b'end_header', b'face',
             b'vertex_indices', b'uchar', b'int', b'float', b'double', b'NumberOfPoints', b'format="appended"',
             b'header_type="UInt64"', b'compressor="vtkZLibDataCompressor"', b'<Polys>', b'<![CDATA[', b'&#0;'],
    'plan': [b'"tip"', b'"axis"', b'"roll_deg"', b'"feed"', b'"poses"', b'"start"', b'"step_mm"', b'"count"',
             b'"reamer"', b'null', b'true', b'[]', b'{}', b'[[[[[[', b'"\\ud800"', b'1e400', b'1000001'],
    'volume': [b'NRRD0004', b'sizes', b'encoding', b'gzip', b'ascii', b'endian', b'big', b'space directions',
               b'space origin', b'(nan,nan,nan)', b'(0,0,0)', b'data file', b'LIST', b'byte skip', b'-1',
               b'spacings', b'space units', b'%d', b'%03d', b'NDims', b'DimSize', b'ElementType', b'MET_DOUBLE',
               b'ElementDataFile', b'LOCAL', b'CompressedData', b'True', b'HeaderSize', b'TransformMatrix',
               b'ElementSpacing', b'ElementNumberOfChannels', b'/dev/zero', b'..', b' = ', b'n+1\0', b'n+2\0',
               b'ni1\0'],
    # DICOM: value representations, delimiters, the pixel data tag, transfer syntaxes, DS/IS text.
    'dicom': [b'OB', b'OW', b'UN', b'SQ', b'UT', b'US', b'DS', b'IS', b'\xff\xff\xff\xff', b'\xfe\xff\x00\xe0',
              b'\xfe\xff\xdd\xe0', b'\xfe\xff\x0d\xe0', b'\xe0\x7f\x10\x00', b'\x28\x00\x10\x00', b'\x28\x00\x11\x00',
              b'\x20\x00\x32\x00', b'\x20\x00\x37\x00', b'\x28\x00\x08\x00', b'1.2.840.10008.1.2',
              b'1.2.840.10008.1.2.1', b'1.2.840.10008.1.2.2', b'1.2.840.10008.1.2.5', b'1.2.840.10008.1.2.4.50',
              b'1.2.840.10008.1.2.4.90', b'1.2.840.10008.1.2.1.99', b'\\', b'\\\\', b'nan', b'1e308', b'-0']}
WORDS['landmarks'] = [b'"side"', b'"right"', b'"left"', b'"unspecified"', b'"glenoid_centre"', b'"trigonum_scapulae"',
                      b'"inferior_angle"', b'"method"', b'null', b'true', b'[]', b'{}', b'[[[[[[', b'"\\ud800"', b'1e400']
WORDS['presets'] = WORDS['plan'] + [b'"name"', b'"diameterMm"', b'"sphereRadiusMm"', b'"meshFile"', b'"/dev/zero"']
NUMBER = re.compile(rb'[-+]?(\d+\.?\d*([eE][-+]?\d+)?|\.\d+)')

# NIfTI header fields (offset, struct format) that say how to read the voxels.
NIFTI1_FIELDS = [(0, '<i'), (40, '<h'), (42, '<h'), (44, '<h'), (46, '<h'), (48, '<h'), (70, '<h'), (72, '<h'),
                 (76, '<f'), (80, '<f'), (84, '<f'), (88, '<f'), (108, '<f'), (112, '<f'), (116, '<f'), (123, '<B'),
                 (252, '<h'), (254, '<h'), (256, '<f'), (260, '<f'), (264, '<f'), (268, '<f'), (280, '<f'),
                 (284, '<f'), (296, '<f'), (312, '<f'), (324, '<f')]
NIFTI2_FIELDS = [(0, '<i'), (12, '<h'), (14, '<h'), (16, '<q'), (24, '<q'), (32, '<q'), (40, '<q'), (48, '<q'),
                 (104, '<d'), (112, '<d'), (120, '<d'), (128, '<d'), (168, '<q'), (176, '<d'), (184, '<d'),
                 (344, '<i'), (348, '<i'), (352, '<d'), (368, '<d'), (376, '<d'), (400, '<d'), (432, '<d'),
                 (500, '<i')]


class Mutator:
    def __init__(self, rng, words):
        self.r = rng
        self.words = words

    def pos(self, d, hot):
        """A position in d, mostly inside the first `hot` bytes (the header)."""
        if hot and self.r.random() < 0.8:
            return self.r.randrange(min(hot, len(d)))
        return self.r.randrange(len(d))

    def number(self, fmt):
        if fmt[-1] in 'fd':
            x = self.r.choice(FLOATS)
            if fmt[-1] == 'f' and abs(x) > 3.4e38 and x == x:
                x = float('inf')  # beyond float32
            return struct.pack(fmt, x)
        bits = 8 * struct.calcsize(fmt)
        v = self.r.choice(INTS + [self.r.randrange(2**bits)])
        return (v % 2**bits).to_bytes(bits // 8, 'little')

    def mutate(self, data, hot=0, fields=()):
        d = bytearray(data)
        for _ in range(self.r.choice([1, 1, 1, 2, 3, 5])):
            if not d:
                d += b'x'
                continue
            op = self.r.randrange(16 if fields else 15)
            L, p = len(d), self.pos(d, hot)
            if op == 0:
                d[p] ^= 1 << self.r.randrange(8)
            elif op == 1:
                d[p] = self.r.randrange(256)
            elif op == 2:
                del d[self.pos(d, hot) if self.r.random() < 0.3 else self.r.randrange(L):]
            elif op == 3:
                del d[p:p + self.r.randrange(1, 64)]
            elif op == 4:
                chunk = d[p:p + self.r.randrange(1, 200)]
                k = self.r.randrange(L)
                d[k:k] = chunk * self.r.choice([1, 2, 10])
            elif op in (5, 6):
                ms = list(NUMBER.finditer(bytes(d[:hot] if hot else d)))
                if ms:
                    m = self.r.choice(ms)
                    d[m.start():m.end()] = self.r.choice(TEXT_NUMBERS)
            elif op == 7:
                d[p:p] = self.r.choice(self.words)
            elif op == 8:
                w = self.r.choice(self.words)
                d[p:p + len(w)] = w
            elif op == 9:
                lines = bytes(d).split(b'\n')
                if len(lines) > 1:
                    a, b = self.r.randrange(len(lines)), self.r.randrange(len(lines))
                    c = self.r.randrange(3)
                    if c == 0:
                        lines.insert(b, lines[a])
                    elif c == 1:
                        del lines[a]
                    else:
                        lines[a], lines[b] = lines[b], lines[a]
                    d = bytearray(b'\n'.join(lines))
            elif op == 10:
                d = bytearray(bytes(d).replace(b'\n', self.r.choice([b'\r\n', b'\r', b'\n\n'])))
            elif op == 11:
                d[p:p] = self.r.choice([b'\xff\xfe', b'\x00', b'\xc3', b'\t', b'\x1a', b'\xef\xbb\xbf'])
            elif op == 12:
                n = self.number(self.r.choice(['<B', '<H', '<I', '<Q']))
                d[p:p + len(n)] = n
            elif op == 13:
                n = self.number(self.r.choice(['<f', '<d']))
                d[p:p + len(n)] = n
            elif op == 14:
                d[p:p] = self.r.choice([b'9', b'a', b'(', b'[', b'{', b'%', b'\\']) * self.r.choice([100, 5000])
            else:  # a header field of a known layout set to an extreme value
                off, fmt = self.r.choice(fields)
                n = self.number(fmt)
                if off + len(n) <= len(d):
                    d[off:off + len(n)] = n
        return bytes(d)

    def mutate_file(self, name, data):
        """Mutates with a bias to the format's header; .gz files mostly through their content."""
        if name.endswith('.gz') and self.r.random() < 0.8:
            try:
                inner = gzip.decompress(data)
            except (OSError, EOFError):
                inner = None
            if inner is not None:
                return gzip.compress(self.mutate_file(name[:-3], inner), mtime=0)
        if len(data) > 256 * 1024:  # a real volume: mutate the header, keep the voxels
            return self.mutate(data[:65536]) + data[65536:]
        hot, fields = 0, ()
        if name.endswith('.nii') and len(data) >= 4:
            v2 = struct.unpack('<i', data[:4])[0] == 540
            hot, fields = (544 if v2 else 352), (NIFTI2_FIELDS if v2 else NIFTI1_FIELDS)
        elif name.endswith('.dcm'):
            hot = data.find(b'\xe0\x7f\x10\x00') + 12 if b'\xe0\x7f\x10\x00' in data else len(data)
        return self.mutate(data, hot, fields)


def ext_of(name):
    return '.nii.gz' if name.endswith('.nii.gz') else os.path.splitext(name)[1]


def link_dir_into(src, dst, skip=()):
    """Makes the files of src visible in dst (symlinks), except those in skip."""
    for f in os.listdir(src):
        s = os.path.join(src, f)
        if f not in skip and os.path.isfile(s) and not os.path.exists(os.path.join(dst, f)):
            os.symlink(os.path.abspath(s), os.path.join(dst, f))


class Runner:
    def __init__(self, args):
        self.a = args
        self.stats = collections.Counter()
        self.messages = collections.Counter()
        self.signatures = {}
        os.makedirs(args.out, exist_ok=True)
        self.env = dict(os.environ,
                        ASAN_OPTIONS='detect_leaks=0:allocator_may_return_null=0:max_allocation_size_mb=512:'
                                     'hard_rss_limit_mb=2500:handle_abort=1:handle_segv=1',
                        UBSAN_OPTIONS='print_stacktrace=1:halt_on_error=1',
                        FUZZ_TIMEOUT=str(args.timeout))

    def run(self, items):
        """items: iterator of (path given to the driver, what to save if it is a finding, what to delete after).
        Inputs are written batch by batch and removed after their batch, so big seeds need little disk."""
        total = 0
        while True:
            chunk = list(itertools.islice(items, self.a.batch))
            if not chunk:
                return total
            total += len(chunk)
            self.run_batch([(p, k) for p, k, _ in chunk])
            for _, _, scratch in chunk:
                (shutil.rmtree if os.path.isdir(scratch) else os.remove)(scratch)

    def run_batch(self, inputs):
        i = 0
        while i < len(inputs):
            batch = inputs[i:i + self.a.batch]
            cmd = ['nice', '-n', '10', self.a.driver, DRIVER_MODE.get(self.a.mode, self.a.mode)] + [p for p, _ in batch]
            try:
                p = subprocess.run(cmd, capture_output=True, env=self.env,
                                   timeout=self.a.timeout * len(batch) + 120)
                out, err, rc = p.stdout.decode(errors='replace'), p.stderr.decode(errors='replace'), p.returncode
            except subprocess.TimeoutExpired as e:
                out, err, rc = (e.stdout or b'').decode(errors='replace'), 'batch timeout', -signal.SIGKILL
            current, done = None, 0
            for line in out.splitlines():
                if line.startswith('@@ '):
                    current = line[3:]
                    continue
                done += 1
                if line.startswith('OK'):
                    self.stats['ok'] += 1
                elif line.startswith('EXC'):
                    self.stats['error'] += 1
                    self.check_message(current, line[4:], dict(batch)[current])
                elif line.startswith('FINDING'):
                    self.stats['finding'] += 1
                    self.save(dict(batch)[current], line, '')
            if rc != 0 and current is None:
                sys.exit(f'the driver failed before reading any input (rc={rc}):\n{err[-2000:]}')
            if rc != 0 and done < len(batch):
                kind = self.classify(rc, err)
                self.stats[kind] += 1
                self.save(dict(batch)[current], f'{kind} rc={rc}', err)
                i += [q for q, _ in batch].index(current) + 1  # go on after the input that stopped the process
            else:
                i += len(batch)

    @staticmethod
    def classify(rc, err):
        if rc == -signal.SIGALRM or rc == -signal.SIGKILL:
            return 'hang'
        if 'allocation-size-too-big' in err or 'requested allocation size' in err or 'rss limit' in err:
            return 'huge-allocation'
        if 'AddressSanitizer' in err:
            return 'asan'
        if 'runtime error' in err:
            return 'ubsan'
        return 'crash'

    def check_message(self, path, msg, keep):
        # "FILE[:LINE]: problem": the message must name the input (its file, or for DICOM its directory).
        name, parent = os.path.basename(path), os.path.basename(os.path.dirname(path))
        if name not in msg and not (self.a.mode == 'dicom' and parent in msg):
            self.stats['unnamed'] += 1
            self.save(keep, 'FINDING message does not name the file: ' + msg, '')
        blank = msg.replace(os.path.dirname(path), 'DIR')
        blank = re.sub(r'/\S*?/(m|d)\d+[^\s:]*', 'FILE', blank)
        self.messages[re.sub(r'-?\d+(\.\d+)?(e[-+]?\d+)?', 'N', blank)[:160]] += 1

    def save(self, path, what, err):
        # Top frames without their absolute addresses (library frames keep their +offset: vtk-dicom has no symbols).
        frames = [re.sub(r'#\d+ 0x[0-9a-f]+ ', '', ln.strip())[:120] for ln in err.splitlines() if re.match(r'\s+#\d+ ', ln)][:3]
        head = [re.sub(r'0x[0-9a-f]+|\d+', 'N', ln) for ln in err.splitlines()
                if 'ERROR' in ln or 'runtime error' in ln][:1]
        signature = (re.sub(r'/\S+', '', what)[:60], tuple(head), tuple(frames))
        h = hashlib.md5(repr(signature).encode()).hexdigest()[:8]
        if h in self.signatures:
            return
        self.signatures[h] = signature
        dst = os.path.join(self.a.out, f'{self.a.mode}_{h}_{os.path.basename(path)}')
        if os.path.isdir(path):
            shutil.copytree(path, dst)
        else:
            shutil.copy(path, dst)
        with open(dst + '.log', 'w') as f:
            f.write(what + '\n' + err[-8000:])
        print('NEW', h, what[:150], '->', dst, flush=True)


def file_units(args, rng, mutator, work):
    """Mutants of every seed file, written beside links to the other files of the seed's directory."""
    seeds = sorted(os.path.join(d, f) for d in args.seeds for f in os.listdir(d)
                   if f.endswith(EXTENSIONS[args.mode]) and os.path.isfile(os.path.join(d, f)))
    for k, s in enumerate(seeds):
        data = open(s, 'rb').read()
        n = args.mutations if len(data) <= 256 * 1024 else max(1, args.mutations // 10)
        wd = os.path.join(work, f's{k}')
        os.makedirs(wd)
        link_dir_into(os.path.dirname(s), wd)
        yield s, mutants_of_file(mutator, s, data, wd, n)


def mutants_of_file(mutator, seed, data, wd, n):
    for m in range(n):
        fn = os.path.join(wd, f'm{m}{ext_of(seed)}')
        with open(fn, 'wb') as f:
            f.write(mutator.mutate_file(seed, data))
        yield fn, fn, fn


def dicom_units(args, rng, mutator, work):
    """Copies of each series with one file mutated; read through the directory or through that file."""
    series = sorted({root for d in args.seeds for root, _, files in os.walk(d) if any(f.endswith('.dcm') for f in files)})
    for k, s in enumerate(series):
        yield s, mutants_of_series(rng, mutator, s, os.path.join(work, f's{k}'), args.mutations)


def mutants_of_series(rng, mutator, series, wd, n):
    files = sorted(f for f in os.listdir(series) if os.path.isfile(os.path.join(series, f)))
    for m in range(n):
        victim = rng.choice(files)
        d = os.path.join(wd, f'd{m}')
        os.makedirs(d)
        for f in files:
            if f != victim:
                shutil.copy(os.path.join(series, f), d)
        with open(os.path.join(d, victim), 'wb') as f:
            f.write(mutator.mutate_file(victim, open(os.path.join(series, victim), 'rb').read()))
        yield (d if rng.random() < 0.6 else os.path.join(d, victim)), d, d


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--driver', required=True)
    ap.add_argument('--mode', required=True, choices=['mesh', 'plan', 'presets', 'landmarks', 'volume', 'dicom'])
    ap.add_argument('--seeds', required=True, action='append', help='seed directory (repeatable)')
    ap.add_argument('--out', required=True, help='where findings are saved')
    ap.add_argument('--mutations', type=int, default=200, help='mutants per seed file or series')
    ap.add_argument('--random-seed', type=int, default=1)
    ap.add_argument('--timeout', type=int, default=10, help='seconds per input before it counts as a hang')
    ap.add_argument('--batch', type=int, default=200, help='inputs per driver process')
    ap.add_argument('--work', default=None, help='scratch directory (default: OUT/work-MODE, removed after)')
    args = ap.parse_args()
    args.seeds = [s for s in args.seeds if os.path.isdir(s)]
    rng = random.Random(args.random_seed)
    mutator = Mutator(rng, WORDS[args.mode] if args.mode != 'dicom' else WORDS['dicom'])
    work = args.work or os.path.join(args.out, f'work-{args.mode}')
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    runner = Runner(args)
    units = dicom_units if args.mode == 'dicom' else file_units
    t0, total = time.time(), 0
    for seed, items in units(args, rng, mutator, work):
        n = runner.run(items)
        total += n
        print(f'{args.mode}: {seed}: {n} inputs, so far {dict(runner.stats)}', flush=True)
    shutil.rmtree(work, ignore_errors=True)
    with open(os.path.join(args.out, f'messages-{args.mode}.tsv'), 'w') as f:
        for msg, n in runner.messages.most_common():
            f.write(f'{n}\t{msg}\n')
    bad = sum(runner.stats[k] for k in ('finding', 'hang', 'huge-allocation', 'asan', 'ubsan', 'crash', 'unnamed'))
    print(f'{args.mode}: {total} inputs in {time.time() - t0:.0f} s: {dict(runner.stats)}; '
          f'{len(runner.signatures)} distinct findings in {args.out}', flush=True)
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
