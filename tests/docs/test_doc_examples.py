"""doc_examples.py itself: on markdown written here, it passes what a run prints, and fails what
it does not print, naming the file, the line, the pasted line and the run's.

Environment: DISPCON_BIN_DIR and DISPCON_PYTHON_DIR (the build's bin/ and python/),
DISPCON_PYTHON_EXECUTABLE (the module's interpreter)."""
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))


def run(markdown):
    """(exit code, output) of doc_examples.py over one README.md holding `markdown`."""
    with tempfile.TemporaryDirectory() as tmp:
        os.symlink(os.path.join(SOURCE, "samples"), os.path.join(tmp, "samples"))
        os.symlink(os.path.join(SOURCE, "freecad_workbench"), os.path.join(tmp, "freecad_workbench"))
        with open(os.path.join(tmp, "README.md"), "w", encoding="utf-8") as f:
            f.write(textwrap.dedent(markdown))
        p = subprocess.run(
            [sys.executable, os.path.join(HERE, "doc_examples.py"), "--source", tmp,
             "--bin", os.environ["DISPCON_BIN_DIR"], "--python", os.environ["DISPCON_PYTHON_DIR"],
             "--python-executable", os.environ.get("DISPCON_PYTHON_EXECUTABLE", "/usr/bin/python3"),
             "--freecad", "no", os.path.join(tmp, "README.md")],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        return p.returncode, p.stdout


def passes_then_fails(test, block, good, bad, *said):
    """The block with `good` in its {n} passes; with `bad` it fails, saying each of `said`."""
    code, out = run(block.format(n=good))
    test.assertEqual(code, 0, out)
    code, out = run(block.format(n=bad))
    test.assertEqual(code, 1, out)
    for text in said:
        test.assertIn(text, out)
    return out


ASSEMBLE = """\
    Text.

    ```text
    $ dispcon assemble samples/fourbar.dcl
    samples/fourbar.dcl: converged in {n} iterations (max residual 1.94482e-12)
    ...
    $ echo $?
    0
    ```
    """


class Shell(unittest.TestCase):
    def test_the_pasted_output_passes_and_a_changed_number_fails_naming_file_and_line(self):
        passes_then_fails(self, ASSEMBLE, 14, 15, "FAIL README.md:3",
                          "README.md:5: the pasted output of `$ dispcon assemble samples/fourbar.dcl` "
                          "(line 4) differs from the run's:",
                          "  pasted: samples/fourbar.dcl: converged in 15 iterations",
                          "  run:    samples/fourbar.dcl: converged in 14 iterations")

    def test_the_elision_is_whole_lines_only(self):
        # Without `...` the body table the run prints after the first line is a difference.
        code, out = run(ASSEMBLE.format(n=14).replace("    ...\n", ""))
        self.assertEqual(code, 1, out)
        self.assertIn("  pasted: (the end of the pasted output)", out)
        self.assertIn("  run:      body            position", out)
        # A line that differs after the elided ones is found too.
        code, out = run(ASSEMBLE.format(n=14).replace("    0\n", "    3\n"))
        self.assertEqual(code, 1, out)
        self.assertIn("README.md:8: the pasted output of `$ echo $?` (line 7)", out)

    def test_an_exit_code_and_a_setup(self):
        code, out = run("""\
            <!-- example: setup printf 'object a;\\nend\\n' > one.dcl -->
            ```
            $ dispcon assemble one.dcl
            one.dcl: converged in 0 iterations (max residual 0)
              body            position                                rotation vector
              a                  0.000000    0.000000    0.000000         0.000000   0.000000   0.000000
            $ dispcon assemble two.dcl
            two.dcl: error: cannot open the file (No such file or directory)
            $ echo $?
            2
            ```
            """)
        self.assertEqual(code, 0, out)

    def test_varies_leaves_out_only_what_it_matches(self):
        block = """\
            <!-- example: varies [0-9]+ ms -->
            ```
            $ echo "took 12 ms, {n} steps"
            took 31 ms, 5 steps
            ```
            """
        passes_then_fails(self, block, 5, 6, "  pasted: took <varies>, 5 steps",
                          "  run:    took <varies>, 6 steps")


class Python(unittest.TestCase):
    def test_values_warnings_and_exceptions_as_the_interpreter_prints_them(self):
        session = """\
            ```python
            >>> import dispcon
            >>> m = dispcon.load("samples/monocycle.dcl")
            sys:1: ModelWarning: samples/monocycle.dcl:65:1: warning: angle max 9 is outside [0, 3.14159]; clamped to 3.14159
            >>> m.assemble().iterations
            {n}
            >>> m.body("nobody")
            ValueError: unknown body 'nobody'
            >>> for k in range(2):
            ...     print(k)
            0
            1
            ```
            """
        passes_then_fails(self, session, 37, 38,
                          "README.md:6: the pasted output of `>>> m.assemble().iterations` (line 5)",
                          "  pasted: 38", "  run:    37")

    def test_a_named_session_spans_blocks_and_others_start_afresh(self):
        code, out = run("""\
            <!-- example: session s -->
            ```
            >>> x = 2
            ```
            <!-- example: session s -->
            ```
            >>> x
            2
            ```
            ```
            >>> x
            NameError: name 'x' is not defined
            ```
            """)
        self.assertEqual(code, 0, out)


class Markers(unittest.TestCase):
    def test_a_skip_is_listed_with_its_reason_and_not_run(self):
        code, out = run("""\
            <!-- example: skip the GUI only -->
            ```
            $ false
            nothing like this
            ```
            ```
            $ echo run
            run
            ```
            """)
        self.assertEqual(code, 0, out)
        self.assertIn("skip README.md:2: the GUI only", out)

    def test_an_unknown_marker_or_one_above_no_example_fails(self):
        code, out = run("""\
            <!-- example: sikp typo -->
            ```
            $ echo a
            a
            ```
            <!-- example: skip a listing -->
            ```sh
            ls
            ```
            """)
        self.assertEqual(code, 1, out)
        self.assertIn("README.md:1: unknown marker `example: sikp`", out)
        self.assertIn("README.md:6: an example marker above a block with no `$ ` or `>>> ` line", out)

    def test_no_example_at_all_fails(self):
        code, out = run("Only text.\n")
        self.assertEqual(code, 1, out)
        self.assertIn("no examples found", out)


if __name__ == "__main__":
    unittest.main()
