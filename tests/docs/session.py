"""Replays `>>>` sessions as the interactive interpreter prints them: an expression statement's
value by its repr, what print() writes, a warning as `<stdin>:1: Category: message`, an exception
as its traceback's last line (`ValueError: ...`). Standard output and standard error together.

Used by doc_examples.py in its own interpreter, and run as a script by freecadcmd (which opens
every argument as a document, so the request comes by environment variables): DOC_SESSIONS_IN
names a JSON file [{"setup": code, "statements": [code, ...]}, ...], DOC_SESSIONS_OUT the JSON
file the outputs go to ([{"setup_error": text or null, "outputs": [text, ...]}, ...]).
"""
import contextlib
import io
import json
import os
import sys
import traceback
import warnings


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """As the interpreter shows a warning: no source line under it, and one attributed above the
    typed statement (a C++ call's stacklevel 2) at `sys:1`, there being nothing above the prompt."""
    if filename == __file__:
        filename, lineno = "sys", 1
    (file or sys.stderr).write(warnings.formatwarning(message, category, filename, lineno, ""))


def _run(source, namespace, out):
    """One statement as the interpreter runs what is typed at its prompt."""
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
        try:
            code = compile(source + "\n", "<stdin>", "single")
            exec(code, namespace)
        except SystemExit:
            raise
        except BaseException as e:  # noqa: B902 - the session prints whatever it raised
            out.write(traceback.format_exception_only(type(e), e)[-1])


def run_session(setup, statements, close=None):
    """The outputs of a session's statements, each in a fresh namespace shared by the session;
    setup (code, not shown in the docs) runs first. Returns (setup_error, outputs)."""
    namespace = {"__name__": "__main__", "__builtins__": __builtins__}
    old_hook = sys.displayhook
    sys.displayhook = sys.__displayhook__
    setup_error = None
    outputs = []
    try:
        with warnings.catch_warnings():  # the interpreter's own filters, reset after the session
            warnings.showwarning = _show_warning
            if setup:
                buf = io.StringIO()
                try:
                    with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(buf):
                        exec(compile(setup, "<setup>", "exec"), namespace)
                except BaseException:  # noqa: B902 - reported as the example's failure
                    setup_error = buf.getvalue() + traceback.format_exc()
            if setup_error is None:
                for source in statements:
                    out = io.StringIO()
                    _run(source, namespace, out)
                    outputs.append(out.getvalue())
    finally:
        sys.displayhook = old_hook
        if close:
            close()
    return setup_error, outputs


def _close_freecad_documents():
    import FreeCAD as App
    for name in list(App.listDocuments()):
        App.closeDocument(name)


def main():
    with open(os.environ["DOC_SESSIONS_IN"], encoding="utf-8") as f:
        sessions = json.load(f)
    close = None
    try:
        import FreeCAD  # noqa: F401
        close = _close_freecad_documents
    except ImportError:
        pass
    for folder in reversed(os.environ.get("DOC_SESSIONS_PATH", "").split(os.pathsep)):
        if folder:
            sys.path.insert(0, folder)
    cwd = os.environ.get("DOC_SESSIONS_CWD")
    if cwd:
        os.chdir(cwd)
    results = []
    for s in sessions:
        setup_error, outputs = run_session(s.get("setup"), s["statements"], close)
        results.append({"setup_error": setup_error, "outputs": outputs})
    with open(os.environ["DOC_SESSIONS_OUT"], "w", encoding="utf-8") as f:
        json.dump(results, f)


if os.environ.get("DOC_SESSIONS_IN"):
    main()
