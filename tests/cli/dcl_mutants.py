#!/usr/bin/env python3
"""Mutated .dcl files through the reader: the same diagnostics, byte for byte.

A rewrite of the reader (or the model's checks) must keep every message, its line:column and the
exit code. This script makes mutants of seed files (a byte or a token deleted, inserted or
replaced, lines doubled, swapped or cut, numbers made inf or nan or malformed, keywords swapped,
floods of errors past the cap, includes of mutated files), all from a fixed random seed, and

  compare OLD NEW [--count N] [--seeds FILE...]
      runs both binaries over the mutants (and the seeds) and compares what each prints (standard
      output, standard error, exit code, and the .dcl that --write writes) byte for byte;
  check NEW GOLDEN / update NEW GOLDEN
      compares NEW's diagnostics (standard error and exit code of `assemble`) on the golden set
      (mutants of the committed test files, which rarely change) with the file GOLDEN, or writes it.

The mutants are written with relative names in a temporary directory beside copies of the seeds,
so that messages do not depend on where the files are and includes find their files.
"""
import argparse
import hashlib
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# What a mutation puts in: the language's words, its troublesome numbers and bytes.
KEYWORDS = ("object constraint include end object1 object2 hinge axial planar sphere circle "
            "cylinder polyline angle twist gear belt rack screw move time label position rotation "
            "fixed rotate mass inertia center velocity spin force torque min max as on rigid left "
            "phase ratio radius pitch world").split()
NUMBERS = ["inf", "-inf", "nan", "NaN", "1e999", "-1e999", "1e-400", "0", "-0", "1.5x", "0x10",
           "1e", ".", "-.5", "+3", "1_000", "3.", "99999999999999999999", "1e308", "-1", "0 0 0",
           "1 2", "1e-300 0 0"]
INSERTS = [";", "\"", "\\", "/*", "*/", "//", "\n", "\x00", "\x7f", "\xc3\xa9", "\t", "{", "#",
           "end", "end;", " ", "\"a\\qb\"", "\"x\\x4", "label \"ok\";"]
TOKEN = re.compile(r'"(?:[^"\\\n]|\\.)*"|[A-Za-z][A-Za-z0-9_.\-]*|[-+]?[0-9.][A-Za-z0-9_.+\-]*|;'
                   r'|\S')

# The golden set's seeds: test files that exist for the reader and the command line.
GOLDEN_SEEDS = ["tests/cli/data/bad.dcl", "tests/cli/data/warning.dcl",
                "tests/cli/data/pendulum.dcl", "tests/cli/data/overconstrained.dcl",
                "src/fuzz/corpus/bennett.dcl", "src/fuzz/corpus/far.dcl",
                "src/fuzz/corpus/fourbar.dcl", "src/fuzz/corpus/slider-crank.dcl",
                "src/fuzz/corpus/robot-arm.dcl", "samples/leg.dcl", "samples/legs.dcl",
                "samples/three-gears.dcl", "samples/welded.dcl"]
GOLDEN_COUNT = 150


def mutate(text, rng):
    """One to three random edits of `text` (bytes as latin-1 characters)."""
    for _ in range(rng.choice((1, 1, 1, 2, 3))):
        tokens = [(m.start(), m.end()) for m in TOKEN.finditer(text)]
        lines = text.split("\n")
        kind = rng.randrange(12)
        if not tokens:
            kind = 0
        if kind == 0:  # a byte inserted
            i = rng.randrange(len(text) + 1)
            text = text[:i] + rng.choice(INSERTS) + text[i:]
        elif kind == 1 and text:  # a byte deleted
            i = rng.randrange(len(text))
            text = text[:i] + text[i + 1:]
        elif kind == 2:  # a token deleted
            a, b = rng.choice(tokens)
            text = text[:a] + text[b:]
        elif kind == 3:  # a token made a keyword
            a, b = rng.choice(tokens)
            text = text[:a] + rng.choice(KEYWORDS) + text[b:]
        elif kind == 4:  # a number made troublesome
            numbers = [t for t in tokens if re.match(r"[-+]?[0-9.]", text[t[0]:t[1]])]
            a, b = rng.choice(numbers or tokens)
            text = text[:a] + rng.choice(NUMBERS) + text[b:]
        elif kind == 5:  # a line doubled (a statement or block given twice)
            i = rng.randrange(len(lines))
            lines.insert(i, lines[i])
            text = "\n".join(lines)
        elif kind == 6 and len(lines) > 1:  # two lines swapped
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
            text = "\n".join(lines)
        elif kind == 7:  # cut short
            text = text[:rng.randrange(len(text) + 1)]
        elif kind == 8:  # a token doubled
            a, b = rng.choice(tokens)
            text = text[:b] + " " + text[a:b] + text[b:]
        elif kind == 9:  # a flood: a line repeated past the error cap, errors of both kinds
            i = rng.randrange(len(lines))
            bad = rng.choice(["object;", "@", "constraint hinge 1 2;", "\x01", "object a; end",
                              lines[i], "1.5x", "object b; mass -1; end"])
            lines.insert(i, "\n".join([bad] * rng.randrange(20, 160)))
            text = "\n".join(lines)
        elif kind == 10:  # two tokens swapped
            (a, b), (c, d) = sorted(rng.sample(tokens, 2)) if len(tokens) > 1 else (tokens[0],) * 2
            if c >= b:
                text = text[:a] + text[c:d] + text[b:c] + text[a:b] + text[d:]
        else:  # an include of another seed, or of itself
            i = rng.randrange(len(lines) + 1)
            target = rng.choice(["leg.dcl", "self.dcl", "missing.dcl", "m_sub.dcl", ".", ""])
            extra = rng.choice(["", " rigid", " on nobody", " position 1 2 3", " rotation 0 0 9",
                                " rigid rigid", " on world rotation 0 0 1"])
            lines.insert(i, 'include "%s" as inc%d%s;' % (target, rng.randrange(3), extra))
            text = "\n".join(lines)
    return text


def seed_texts(paths):
    out = []
    for p in paths:
        with open(os.path.join(ROOT, p), "rb") as f:
            out.append((os.path.basename(p), f.read().decode("latin-1")))
    return out


def make_mutants(directory, seeds, count, rng_seed):
    """Writes the seeds and `count` mutants into `directory`; returns the files to read."""
    rng = random.Random(rng_seed)
    files = []
    for name, text in seeds:
        with open(os.path.join(directory, name), "wb") as f:
            f.write(text.encode("latin-1"))
        files.append(name)
    # A file that includes itself, and a mutated sub-model that mutants include.
    with open(os.path.join(directory, "self.dcl"), "wb") as f:
        f.write(b'include "self.dcl" as me;\nobject a; end\n')
    for i in range(count):
        name, text = seeds[rng.randrange(len(seeds))]
        text = mutate(text, rng)
        sub = mutate(seeds[rng.randrange(len(seeds))][1], rng)
        mutant = "m%04d.dcl" % i
        with open(os.path.join(directory, "m_sub.dcl"), "wb") as f:
            f.write(sub.encode("latin-1"))
        # Each mutant with its own sub-model: the pair is one case.
        with open(os.path.join(directory, "m%04d_sub.dcl" % i), "wb") as f:
            f.write(sub.encode("latin-1"))
        with open(os.path.join(directory, mutant), "wb") as f:
            f.write(text.replace('"m_sub.dcl"', '"m%04d_sub.dcl"' % i).encode("latin-1"))
        files.append(mutant)
    return files


def run(binary, directory, name, full):
    """What the binary prints for the file: `assemble` (and, when `full`, --json and --write)."""
    out = []
    commands = [["assemble", name, "--max-iterations", "200"]]
    if full:
        commands.append(["assemble", name, "--max-iterations", "200", "--json",
                         "--write", "written.out"])
    for args in commands:
        written = os.path.join(directory, "written.out")
        if os.path.exists(written):
            os.remove(written)
        p = subprocess.run([binary] + args, cwd=directory, capture_output=True, timeout=120)
        out.append(b"$ %s\nexit %d\n" % (" ".join(args).encode(), p.returncode))
        if full:
            out.append(p.stdout)
        out.append(p.stderr)
        if full and os.path.exists(written):
            with open(written, "rb") as f:
                out.append(b"--write:\n" + f.read())
    return b"".join(out)


def compare(args):
    seeds = args.seeds or sorted(
        [os.path.join("samples", f) for f in os.listdir(os.path.join(ROOT, "samples"))
         if f.endswith(".dcl")] + GOLDEN_SEEDS)
    seeds = sorted(set(seeds))
    with tempfile.TemporaryDirectory() as d:
        files = make_mutants(d, seed_texts(seeds), args.count, args.random_seed)
        differ = 0
        for i, name in enumerate(files):
            a = run(os.path.abspath(args.old), d, name, True)
            b = run(os.path.abspath(args.new), d, name, True)
            if a != b:
                differ += 1
                if differ <= 5:
                    sys.stdout.write("DIFFERS: %s\n--- old\n%s\n--- new\n%s\n" % (
                        name, a.decode("latin-1")[:3000], b.decode("latin-1")[:3000]))
                    shutil.copy(os.path.join(d, name), os.path.join(args.keep, name))
        print("%d files (%d seeds, %d mutants): %d differ" % (
            len(files), len(seeds), args.count, differ))
        return 1 if differ else 0


def golden_text(binary):
    seeds = seed_texts(GOLDEN_SEEDS)
    out = []
    for (name, text), path in zip(seeds, GOLDEN_SEEDS):
        digest = hashlib.sha256(text.encode("latin-1")).hexdigest()[:16]
        out.append("seed %s %s\n" % (path, digest))
    with tempfile.TemporaryDirectory() as d:
        for name in make_mutants(d, seeds, GOLDEN_COUNT, 14):
            out.append(run(binary, d, name, False).decode("latin-1"))
    return "".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="mode", required=True)
    c = sub.add_parser("compare")
    c.add_argument("old")
    c.add_argument("new")
    c.add_argument("--count", type=int, default=3000)
    c.add_argument("--random-seed", type=int, default=1)
    c.add_argument("--seeds", nargs="*")
    c.add_argument("--keep", default=".", help="where the first differing mutants are copied")
    for mode in ("check", "update"):
        g = sub.add_parser(mode)
        g.add_argument("new")
        g.add_argument("golden")
    args = ap.parse_args()
    if args.mode == "compare":
        return compare(args)
    text = golden_text(os.path.abspath(args.new))
    if args.mode == "update":
        with open(args.golden, "w", encoding="latin-1", newline="") as f:
            f.write(text)
        return 0
    with open(args.golden, encoding="latin-1", newline="") as f:
        expected = f.read()
    if text == expected:
        print("%d mutants: the same diagnostics as %s" % (GOLDEN_COUNT, args.golden))
        return 0
    for line in expected.splitlines():
        if line.startswith("seed ") and line + "\n" not in text:
            print("a seed file changed (%s): regenerate the golden file with 'update' from a "
                  "binary whose messages are known good" % line)
            return 1
    exp, got = expected.split("\n$ "), text.split("\n$ ")
    for a, b in zip(exp, got):
        if a != b:
            print("first difference:\n--- expected\n$ %s\n--- got\n$ %s" % (a[:2000], b[:2000]))
            break
    return 1


if __name__ == "__main__":
    sys.exit(main())
