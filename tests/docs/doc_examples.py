#!/usr/bin/env python3
"""Runs the examples pasted in README.md and docs/*.md and compares their output with what is
pasted (the convention: docs/ci.md, "Examples in the docs are run").

An example is a fenced block with a `$ ` line (a shell session) or a `>>> ` line (a Python
session). Shell sessions run in bash from a scratch folder laid out as the repository
(samples/, build/bin/dispcon, build/python, build/samples: the FreeCAD samples), with `dispcon`
on PATH; Python sessions in /usr/bin/python3 with build/python on the path, or in freecadcmd.
Marker comments on the lines right above a block: `<!-- example: skip REASON -->`,
`<!-- example: freecadcmd -->`, `<!-- example: varies REGEX -->`, `<!-- example: setup ... -->`.

    doc_examples.py --source DIR --bin DIR --python DIR [--fcstd DIR] [--freecad only|no] [FILE...]

Exit 0 when every example run printed what is pasted; 1 otherwise, each difference named by
file, line, the pasted line and the line the run printed.
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ELISION = "..."        # an output line of only this: any number of lines, none included
VARIES = "\x00varies\x00"
SEPARATOR = "\x1e"
SHOWN = 40             # the lines of a run's output a failure shows, at most


class Example:
    def __init__(self, path, line, kind, body, options):
        self.path, self.line, self.kind, self.body = path, line, kind, body
        self.skip = options.get("skip")
        self.setup = options.get("setup")
        self.varies = [re.compile(v) for v in options.get("varies", [])]
        self.freecadcmd = "freecadcmd" in options
        # Python blocks of one file with the same session name run in one namespace, in order.
        self.session = options.get("session")
        self.items = []   # (line, command or statement, [(line, expected output line)])
        self.error = None
        # FreeCAD runs in it: a freecadcmd Python session, or a shell session over .FCStd files.
        text = "\n".join(t for _, t in body)
        self.needs_freecad = self.freecadcmd or (kind == "shell" and
                                                  (".FCStd" in text or "freecadcmd" in text))
        if kind == "shell":   # a command goes on after a line ending in a backslash
            self._parse("$ ", lambda t, item: item[1].endswith("\\"), lambda t: t)
        else:                 # a statement goes on on its `... ` lines
            self._parse(">>> ", lambda t, item: t.startswith("... "), lambda t: t[4:])

    def where(self, line=None):
        return "%s:%d" % (self.path, line if line is not None else self.line)

    def _parse(self, prompt, goes_on, continuation):
        """self.items from the body: each prompt line an item, its continuation lines (before
        any output) joined to it, the lines up to the next prompt its expected output."""
        item = None
        for n, t in self.body:
            if item is not None and not item[2] and goes_on(t, item):
                item[1] += "\n" + continuation(t)
            elif t.startswith(prompt) or t == prompt.strip():
                item = [n, t[len(prompt):], []]
                self.items.append(item)
            elif item is None:
                if t.strip():
                    self.error = "%s: output before the first `%s` line" % (self.where(n), prompt)
                    return
            else:
                item[2].append((n, t))


def parse_markdown(path, shown):
    """The examples of one markdown file, and the errors of its markers."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    examples, errors = [], []
    options, marker_line = {}, None
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.match(r"^\s*<!--\s*example:\s*(\S+)(.*)$", line)
        if m:
            word, rest = m.group(1), m.group(2)
            start = i
            text = rest
            while "-->" not in text:
                i += 1
                if i == len(lines):
                    errors.append("%s:%d: unclosed `<!-- example:` comment" % (shown, start + 1))
                    return examples, errors
                text += "\n" + lines[i]
            text = text[:text.index("-->")]
            if word == "skip":
                options["skip"] = text.strip() or "(no reason given)"
            elif word == "freecadcmd":
                options["freecadcmd"] = True
            elif word == "session":
                options["session"] = text.strip()
            elif word == "varies":
                options.setdefault("varies", []).append(text.strip())
            elif word == "setup":
                options["setup"] = (options.get("setup", "") + text.lstrip("\n").rstrip() + "\n")
            else:
                errors.append("%s:%d: unknown marker `example: %s` (skip, freecadcmd, session, varies, setup)"
                              % (shown, start + 1, word))
            marker_line = marker_line or start + 1
            i += 1
            continue
        fence = re.match(r"^(\s*)(`{3,}|~{3,})(.*)$", line)
        if fence:
            indent, mark = len(fence.group(1)), fence.group(2)
            start = i
            body = []
            i += 1
            while i < len(lines):
                close = re.match(r"^\s*" + re.escape(mark[0]) + "{%d,}\\s*$" % len(mark), lines[i])
                if close:
                    break
                t = lines[i]
                body.append((i + 1, t[indent:] if t[:indent].strip() == "" else t.lstrip()))
                i += 1
            kind = None
            for _, t in body:
                if t.startswith("$ "):
                    kind = "shell"
                    break
                if t.startswith(">>> ") or t == ">>>":
                    kind = "python"
                    break
            if kind:
                examples.append(Example(shown, start + 1, kind, [(n, t.rstrip()) for n, t in body],
                                        options))
            elif options:
                errors.append("%s:%d: an example marker above a block with no `$ ` or `>>> ` line"
                              % (shown, marker_line))
            options, marker_line = {}, None
            i += 1
            continue
        if options and line.strip():
            errors.append("%s:%d: an example marker not right above a fenced block"
                          % (shown, marker_line))
            options, marker_line = {}, None
        i += 1
    return examples, errors


def normalise(text, varies):
    text = text.rstrip()
    for v in varies:
        text = v.sub(VARIES, text)
    return text


def compare(expected, actual, varies):
    """None when the actual lines match the expected ones (an ELISION line matching any run of
    lines), else (expected line number or None, expected text, actual text) at the first place
    no match gets past."""
    exp = [(n, normalise(t, varies)) for n, t in expected]
    act = [normalise(t, varies) for t in actual]
    while act and not act[-1]:
        act.pop()
    while exp and not exp[-1][1]:
        exp.pop()
    best = [(0, 0)]   # the furthest (expected, actual) reached

    memo = {}

    def match(i, j):
        key = (i, j)
        if key in memo:
            return memo[key]
        if (i, j) > best[0]:
            best[0] = (i, j)
        if i == len(exp):
            result = j == len(act)
        elif exp[i][1].strip() == ELISION:
            result = any(match(i + 1, k) for k in range(j, len(act) + 1))
        else:
            result = j < len(act) and exp[i][1] == act[j] and match(i + 1, j + 1)
        memo[key] = result
        return result

    sys.setrecursionlimit(max(10000, 4 * (len(exp) + len(act))))
    if match(0, 0):
        return None
    i, j = best[0]
    while i < len(exp) and exp[i][1].strip() == ELISION:
        i += 1
    line = exp[i][0] if i < len(exp) else (exp[-1][0] + 1 if exp else None)
    return (line, exp[i][1] if i < len(exp) else "(the end of the pasted output)",
            act[j] if j < len(act) else "(the end of the run's output)", j)


def show(text):
    return text.replace(VARIES, "<varies>")


def sandbox(args, tmp):
    """A folder laid out as the repository, for the examples' relative paths."""
    os.symlink(os.path.join(args.source, "samples"), os.path.join(tmp, "samples"))
    os.symlink(os.path.join(args.source, "freecad_workbench"), os.path.join(tmp, "freecad_workbench"))
    os.makedirs(os.path.join(tmp, "build"))
    os.symlink(args.bin, os.path.join(tmp, "build", "bin"))
    os.symlink(args.python, os.path.join(tmp, "build", "python"))
    if args.fcstd:   # a copy: what an example writes must not reach the fixture others read
        shutil.copytree(args.fcstd, os.path.join(tmp, "build", "samples"), symlinks=True)


def environment(args, tmp):
    env = dict(os.environ)
    env["PATH"] = os.path.join(tmp, "build", "bin") + os.pathsep + env.get("PATH", "")
    env["DISPCON_PYTHONPATH"] = args.python
    env.pop("PYTHONPATH", None)
    return env


def run_shell(example, args, tmp):
    """Each command's output (standard output and error together), in one bash, in order."""
    script = ["cd %s || exit 99" % quote(tmp)]
    if example.setup:
        script.append("{\n%s\n} >/dev/null 2>&1 || { echo 'setup failed'; exit 98; }" % example.setup)
    script.append("(exit 0)")
    for k, (_, command, _) in enumerate(example.items):
        script.append("__rc=$?; printf '\\n%s%d%s\\n'; (exit $__rc)" % (SEPARATOR, k, SEPARATOR))
        script.append(command)
    script.append("printf '\\n%send%s\\n'" % (SEPARATOR, SEPARATOR))
    env = environment(args, tmp)
    try:
        p = subprocess.run(["bash", "-c", "\n".join(script)], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, env=env, timeout=300)
    except subprocess.TimeoutExpired:
        return None, "timed out after 300 s"
    text = p.stdout.decode("utf-8", "replace")
    parts = re.split("\n" + SEPARATOR + r"(\d+|end)" + SEPARATOR + "\n", text)
    if not parts[0].startswith(SEPARATOR) and parts[0].strip():
        return None, "the setup printed or failed: " + parts[0]
    outputs = {}
    for tag, chunk in zip(parts[1::2], parts[2::2]):
        if tag != "end":
            outputs[int(tag)] = chunk
    if len(outputs) != len(example.items) or "end" not in parts[1::2]:
        return None, "the session stopped early:\n" + text
    return [outputs[k].split("\n") if outputs[k] else [] for k in range(len(example.items))], None


def quote(s):
    return "'" + s.replace("'", "'\\''") + "'"


def run_python(examples, args, tmp, freecad):
    """Every session of `examples` in one interpreter (python3, or freecadcmd), each in a
    namespace of its own. Returns a list of (outputs or None, error or None)."""
    if not examples:
        return []
    groups, request = [], []   # the examples of each session, in order
    named = {}
    for e in examples:
        key = (e.path, e.session)
        if e.session and key in named:
            groups[named[key]].append(e)
            request[named[key]]["statements"] += [s for _, s, _ in e.items]
            if e.setup:
                request[named[key]]["setup"] = (request[named[key]]["setup"] or "") + e.setup
            continue
        named[key] = len(groups)
        groups.append([e])
        request.append({"setup": e.setup, "statements": [s for _, s, _ in e.items]})
    inp, out = os.path.join(tmp, ".sessions-in.json"), os.path.join(tmp, ".sessions-out.json")
    with open(inp, "w", encoding="utf-8") as f:
        json.dump(request, f)
    if os.path.exists(out):
        os.remove(out)
    env = environment(args, tmp)
    env.update(DOC_SESSIONS_IN=inp, DOC_SESSIONS_OUT=out, DOC_SESSIONS_CWD=tmp)
    session = os.path.join(HERE, "session.py")
    if freecad:
        env["DOC_SESSIONS_PATH"] = os.pathsep.join(
            [args.python, os.path.join(args.source, "freecad_workbench"),
             os.path.join(args.source, "samples", "freecad")])
        command = [args.freecadcmd, session]
    else:
        env["PYTHONPATH"] = args.python
        command = [args.python_executable, session]
    try:
        p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                           timeout=600, cwd=tmp)
    except subprocess.TimeoutExpired:
        return [(None, "timed out after 600 s")] * len(examples)
    if not os.path.exists(out):
        text = p.stdout.decode("utf-8", "replace")
        return [(None, "%s wrote no result:\n%s" % (command[0], text))] * len(examples)
    with open(out, encoding="utf-8") as f:
        results = json.load(f)
    answers = {}
    for group, r in zip(groups, results):
        outputs = [o.split("\n") if o else [] for o in r["outputs"]]
        for e in group:
            if r["setup_error"]:
                answers[id(e)] = (None, "the setup failed:\n" + r["setup_error"])
            else:
                answers[id(e)] = (outputs[:len(e.items)], None)
                outputs = outputs[len(e.items):]
    return [answers[id(e)] for e in examples]


def check(example, outputs, error):
    """The failure messages of one example (none when it printed what is pasted)."""
    if error:
        return ["%s: %s" % (example.where(), error)]
    failures = []
    for (line, item, expected), actual in zip(example.items, outputs):
        if actual and actual[-1] == "":
            actual = actual[:-1]
        difference = compare(expected, actual, example.varies)
        if difference is None:
            continue
        at, want, got, j = difference
        prompt = "$ " if example.kind == "shell" else ">>> "
        first = item.split("\n")[0]
        message = ["%s: the pasted output of `%s%s` (line %d) differs from the run's:"
                   % (example.where(at if at else line), prompt, first, line),
                   "  pasted: %s" % show(want),
                   "  run:    %s" % show(got)]
        if len(actual) <= SHOWN:
            message.append("  the run printed (%d lines):" % len(actual))
            message += ["  | " + t for t in actual]
        else:   # around the difference
            lo = max(0, min(j - SHOWN // 2, len(actual) - SHOWN))
            message.append("  the run printed (lines %d-%d of %d):" % (lo + 1, lo + SHOWN, len(actual)))
            message += ["  | " + t for t in actual[lo:lo + SHOWN]]
        failures.append("\n".join(message))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True, help="the repository")
    parser.add_argument("--bin", required=True, help="the folder of the dispcon binary")
    parser.add_argument("--python", required=True, help="the folder of the dispcon module")
    parser.add_argument("--fcstd", help="the FreeCAD samples (build_samples.py's output)")
    parser.add_argument("--python-executable", default="/usr/bin/python3")
    parser.add_argument("--freecadcmd", default=shutil.which("freecadcmd"))
    parser.add_argument("--freecad", choices=["only", "no", "both"], default="both",
                        help="run the examples that need FreeCAD, the others, or both")
    parser.add_argument("files", nargs="*", help="markdown files (default: README.md docs/*.md)")
    args = parser.parse_args()
    for name in ("source", "bin", "python", "fcstd"):
        if getattr(args, name):
            setattr(args, name, os.path.abspath(getattr(args, name)))

    files = args.files or [os.path.join(args.source, "README.md")] + sorted(
        glob.glob(os.path.join(args.source, "docs", "*.md")))
    examples, failures = [], []
    for path in files:
        shown = os.path.relpath(os.path.abspath(path), args.source)
        found, errors = parse_markdown(path, shown)
        examples += found
        failures += errors
    failures += [e.error for e in examples if e.error]
    markup = len(failures)   # markers and blocks the convention cannot read
    examples = [e for e in examples if not e.error]
    if not examples:
        failures.append("no examples found in %s" % ", ".join(files))

    chosen = [e for e in examples
              if args.freecad == "both" or (e.needs_freecad == (args.freecad == "only"))]
    skipped = [e for e in chosen if e.skip]
    if not args.freecadcmd or not args.fcstd:
        for e in chosen:
            if e.needs_freecad and not e.skip:
                e.skip = "FreeCAD is not installed" if not args.freecadcmd else "no --fcstd samples"
                skipped.append(e)
    runnable = [e for e in chosen if not e.skip]

    passed = 0
    with tempfile.TemporaryDirectory(prefix="doc-examples-") as tmp:
        sandbox(args, tmp)
        results = {}
        for e in runnable:
            if e.kind == "shell":
                results[id(e)] = run_shell(e, args, tmp)
        for freecad in (False, True):
            group = [e for e in runnable if e.kind == "python" and e.freecadcmd == freecad]
            for e, r in zip(group, run_python(group, args, tmp, freecad)):
                results[id(e)] = r
        for e in runnable:
            outputs, error = results[id(e)]
            problems = check(e, outputs, error)
            if problems:
                failures += problems
                print("FAIL %s (%s, %d %s)" % (e.where(), e.kind, len(e.items),
                                               "commands" if e.kind == "shell" else "statements"))
            else:
                passed += 1
                print("ok   %s (%s, %d %s)" % (e.where(), e.kind, len(e.items),
                                               "commands" if e.kind == "shell" else "statements"))
    for e in skipped:
        print("skip %s: %s" % (e.where(), e.skip))
    if failures:
        print()
        print("\n\n".join(failures))
    print("\n%d examples run: %d printed what is pasted, %d did not; %d skipped; %d markup errors"
          % (len(runnable), passed, len(runnable) - passed, len(skipped), markup))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
