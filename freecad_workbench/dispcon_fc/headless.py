"""`dispcon check|sweep|drag|assemble FILE.FCStd` inside freecadcmd: the command line parses the
arguments and hands them over as a JSON request; this module does the work and hands back the
exit code and what to print. Exit codes and JSON keys are those of the .dcl subcommands
(cli.md): 0 done, 2 bad input (nothing done), 3 solved as far as possible but something still
fails (a joint, a lock-up, parts that collide)."""
import io
import json
import math
import os
import traceback

from . import motion_svg, studies


def run(request):
    """(exit code, standard output, standard error) of one request (a dict)."""
    out, err = io.StringIO(), io.StringIO()
    try:
        code = _COMMANDS[request["command"]](request, out, err)
    except studies.StudyError as e:
        err.write(str(e) + "\n")
        code = 2
    return code, out.getvalue(), err.getvalue()


def _options(req):
    return {"tolerance": req.get("tolerance"), "max_iterations": req.get("max_iterations")}


def _open(req):
    return studies.open_assembly(req["file"], req.get("assembly"))


def _write(path, text, err):
    try:
        with open(path, "w") as f:
            f.write(text)
        return True
    except OSError as e:
        err.write("%s: error: cannot write the file (%s)\n" % (path, e.strerror))
        return False


def _emit(req, out, doc_json, text):
    if req.get("json"):
        out.write(json.dumps(doc_json, indent=2, allow_nan=False, default=_nan) + "\n")
    else:
        out.write(text)


def _nan(x):
    return None


def _clean(x):
    """JSON has no NaN: a joint without a value is null."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_clean(v) for v in x]
    return x


def _quote(labels):
    return ", ".join("'%s'" % t for t in labels)


def _check(req, out, err):
    doc, asm = _open(req)
    r = studies.check(asm, interference=not req.get("no_interference"), **_options(req))
    lines = ["%s: %s" % (req["file"], r["diagnosis"]), "degrees of freedom: %d" % r["dof"]]
    lines += ["  %s: %d" % (label, b["dof"]) for label, b in r["bodies"].items()]
    for key, what in (("redundant", "redundant"), ("conflicting", "conflicting"),
                      ("limits_active", "limits in contact")):
        if r[key]:
            lines.append("%s: %s" % (what, _quote(r[key])))
    lines += r["advice"]
    for hit in r["interference"]:
        lines.append("interference: '%s' and '%s' overlap, volume %.6g" % (hit["parts"][0], hit["parts"][1],
                                                                          hit["volume"]))
    _emit(req, out, _clean(r), "\n".join(lines) + "\n")
    return studies.check_exit(r)


def _sweep(req, out, err):
    doc, asm = _open(req)
    study = studies.sweep(asm, req["joint"], req.get("from"), req.get("to"), req.get("steps") or 360,
                          interference=not req.get("no_interference"), **_options(req))
    if req.get("csv") and not _write(req["csv"], study.csv(), err):
        return 2
    if req.get("plot") and not _write(req["plot"], motion_svg.sweep_plot_svg(study), err):
        return 2
    if req.get("svg") and not _write(req["svg"], motion_svg.sweep_svg(study, req.get("view") or "iso"), err):
        return 2
    _emit(req, out, _clean(study.to_json()), "%s: %s\n" % (req["file"], study.message))
    return study.exit_code()


def _save(req, doc):
    """--write OUT, or --in-place alone (_refuse_in_place_alone has refused the input as OUT
    without --in-place before anything was done)."""
    target = req.get("write") or (req["file"] if req.get("in_place") else None)
    if target is None:
        return
    try:
        if req.get("write"):
            doc.saveAs(os.path.abspath(target))
        else:
            doc.save()
    except Exception as e:  # FreeCAD raises its own exception types for unwritable files
        detail = e.args[0].get("swhat", e) if e.args and isinstance(e.args[0], dict) else e
        raise studies.StudyError("%s: error: cannot write the document (%s)" % (target, detail))
    # FreeCAD 0.20 may report a failed save on its console only.
    if not os.path.isfile(target):
        raise studies.StudyError("%s: error: cannot write the document" % target)


def _refuse_in_place_alone(req, err):
    if req.get("write") and os.path.realpath(req["write"]) == os.path.realpath(req["file"]) \
            and not req.get("in_place"):
        err.write("%s: error: --write names the input file: add --in-place to overwrite it\n"
                  % req["write"])
        return True
    return False


def _assemble(req, out, err):
    if _refuse_in_place_alone(req, err):
        return 2
    doc, asm = _open(req)
    r = studies.assemble(asm, **_options(req))
    if r["converged"]:
        _save(req, doc)
    text = ["%s: %s" % (req["file"], r["message"]), "  %-16s%s" % ("part", "position")]
    for label, b in r["bodies"].items():
        p = b["position"]
        text.append("  %-16s%12.6f%12.6f%12.6f" % (label, p[0], p[1], p[2]))
    _emit(req, out, _clean(r), "\n".join(text) + "\n")
    return 0 if r["converged"] else 3


def _drag(req, out, err):
    if _refuse_in_place_alone(req, err):
        return 2
    doc, asm = _open(req)
    r, study = studies.drag(asm, req["body"], req["to"], req.get("rotation"), req.get("steps") or 50,
                            **_options(req))
    if req.get("csv") and not _write(req["csv"], studies.drag_csv(study), err):
        return 2
    if req.get("svg"):
        clearance = studies.clearance_of(study.study)
        colliding = [clearance.at(pls) for pls in study.placements]
        if not _write(req["svg"], motion_svg.drag_svg(study, colliding, req.get("view") or "iso"), err):
            return 2
    if study.converged:
        _save(req, doc)
    _emit(req, out, _clean(r), "%s: %s\n" % (req["file"], r["message"]))
    return 0 if study.converged else 3


_COMMANDS = {"check": _check, "sweep": _sweep, "assemble": _assemble, "drag": _drag}


def main():
    """The runner's entry: the request is the JSON file named by DISPCON_FC_REQUEST; the answer,
    {"exit", "stdout", "stderr"}, goes to the request's "result" file (freecadcmd's own exit code
    and output are not to be trusted: it prints a banner and may exit 0 whatever happens)."""
    with open(os.environ["DISPCON_FC_REQUEST"]) as f:
        request = json.load(f)
    try:
        code, stdout, stderr = run(request)
    except Exception:
        code, stdout, stderr = 2, "", "%s: error: %s" % (request.get("file", "?"), traceback.format_exc())
    with open(request["result"], "w") as f:
        json.dump({"exit": code, "stdout": stdout, "stderr": stderr}, f)
