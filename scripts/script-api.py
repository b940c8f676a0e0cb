#!/usr/bin/env python3
"""SimTwo's script API against S2Sim's coverage of it, from two tables:

  ../shared/docs/simtwo-registered-routines.tsv   every routine SimTwo registers (name, Pascal
                                                   signature, unit, category)
  plugins/pascal_script/routines.tsv               what S2Sim does with each (status, note, call)

  script-api.py script OUT.pas       one script that calls every routine once, each call in its
                                     own try, reporting "ROUTINE <name> ok" or "... raised <msg>"
  script-api.py expect STDERR.txt    checks a run's reports against the statuses
  script-api.py docs                 rewrites docs/scripting.md's coverage table
  script-api.py check-docs           fails when that table is stale

Exit 77 (a skip for ctest) when the shared list is absent (S2SIM_SIMTWO_ROUTINES names another).
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("S2SIM_SIMTWO_ROUTINES",
                        os.path.join(ROOT, "..", "shared", "docs", "simtwo-registered-routines.tsv"))
COVERAGE = os.path.join(ROOT, "plugins", "pascal_script", "routines.tsv")
DOCS = os.path.join(ROOT, "docs", "scripting.md")
BEGIN, END = "<!-- coverage table: scripts/script-api.py docs -->", "<!-- end of the coverage table -->"
STATUSES = ("yes", "differs", "rendering", "missing")
SKIP = 77


def read_tsv(path):
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            rows.append(line.rstrip("\n").split("\t"))
    return rows[0], rows[1:]


def load():
    if not os.path.exists(SHARED):
        print(f"skipped: {os.path.normpath(SHARED)} is absent", file=sys.stderr)
        sys.exit(SKIP)
    _, shared = read_tsv(SHARED)
    _, cover = read_tsv(COVERAGE)
    status = {}
    for row in cover:
        row += [""] * (4 - len(row))
        name, st, note, call = row[:4]
        if st not in STATUSES:
            sys.exit(f"{COVERAGE}: {name}: status '{st}' is not one of {', '.join(STATUSES)}")
        if name in status:
            sys.exit(f"{COVERAGE}: {name} is listed twice")
        status[name] = (st, note, call)
    names = [r[0] for r in shared]
    missing = [n for n in names if n not in status]
    extra = [n for n in status if n not in names]
    if missing or extra:
        sys.exit(f"{COVERAGE} does not match {SHARED}: without a row: {', '.join(missing) or '-'}; "
                 f"not in SimTwo's list: {', '.join(extra) or '-'}")
    return [(r[0], r[1], r[2], r[3]) + status[r[0]] for r in shared]


# --- the all-routines script ----------------------------------------------------------------

DEFAULTS = {
    "integer": "0", "longint": "0", "longword": "0", "byte": "1", "word": "0", "smallint": "0",
    "int64": "0", "double": "0.5", "single": "0.5", "extended": "0.5", "string": "'a'",
    "anystring": "'a'", "boolean": "true", "matrix": "Meye(3)", "tcolor": "clRed", "char": "'a'",
    "taxispoint": "vAP", "tmotorpars": "GetMotorPars(0, 0)", "taxisstate": "GetAxisState(0, 0)",
}


def parameters(signature):
    """[(name, type, by_reference)] from 'Function F( a, b : integer; var c : double) : T'."""
    m = re.search(r"\((.*)\)", signature)
    if not m:
        return []
    params = []
    for group in m.group(1).split(";"):
        if ":" not in group:
            continue
        names, typ = group.rsplit(":", 1)
        names = names.strip()
        by_ref = bool(re.match(r"(var|out)\s", names))
        names = re.sub(r"^(var|out|const)\s+", "", names)
        for n in names.split(","):
            params.append((n.strip(), typ.strip().lower(), by_ref))
    return params


SIMPLE_RESULTS = {"double", "extended", "single", "integer", "longint", "int64", "longword", "word",
                  "byte", "smallint", "boolean", "string", "anystring", "char", "widechar"}


def result_type(signature):
    m = re.match(r"\s*function\s+\w+\s*(\(.*\))?\s*:\s*(\w+)", signature, re.I)
    return m.group(2).lower() if m else None


def call_of(name, signature, call):
    """The statement that calls `name`; a simple result is kept in a Variant (a statement cannot
    be the bare call of a compiler intrinsic such as Length or Round)."""
    text = call or default_call(name, signature)
    if result_type(signature) in SIMPLE_RESULTS and ":=" not in text:
        return "vV := " + text
    return text


def default_call(name, signature):
    args = []
    for _, typ, by_ref in parameters(signature):
        if by_ref or typ not in DEFAULTS:
            raise SystemExit(f"{COVERAGE}: {name} needs a call (parameter of type '{typ}')")
        args.append(DEFAULTS[typ])
    return f"{name}({', '.join(args)})" if args else name


PRELUDE = """\
var
  vd, vd2: double; vI: integer; vS: string; vW: WideString; vM: Matrix; vBuf: TUDPBuffer;
  vV, vVA: Variant; vDA: TDoubleDynArray; vSet: set of byte; vAP: TAxisPoint; vP3: TPoint3D;
  vLw1, vLw2: Longword; vFile, vWp: string; vSL: TStringList; called: boolean;

procedure Report(const name, outcome: string);
begin
  WriteLn('ROUTINE ' + name + ' ' + outcome);
end;

procedure Initialize;
begin
  called := false;
end;

procedure Control;
begin
  if called then exit;
  called := true;
  vFile := 'matrix.txt';  { relative: in the script's folder, as SimTwo's project folder }
  Msave(Meye(2), vFile);
  vWp := 'waypoints.xml';
  vSL := TStringList.Create;
  vSL.Text := '<joint_waypoints><state ID="a" final_time="1"><joint ID="shoulder" theta="10"/></state></joint_waypoints>';
  vSL.SaveToFile(GetEnvironmentVariable('S2SIM_SCRIPT_API_DIR') + '/' + vWp);
  vSL.Free;
  vS := 'abc'; vW := 'abc'; vM := Meye(3); vVA := VarArrayCreate([0, 2], varVariant);
  SetLength(vDA, 2); vAP.pos := 0.1; vAP.speed := 0; vAP.final_time := 1;
  AddAxisTrajPoint(0, 0, vAP);
  AddAxisTrajPoint(0, 0, vAP);
"""


def script(rows):
    out = ["{ Generated by scripts/script-api.py from SimTwo's list of registered routines: every",
           "  routine called once, in the list's order, each in its own try. Do not edit. }", PRELUDE]
    for name, signature, _unit, _category, _st, _note, call in rows:
        out.append(f"  try {call_of(name, signature, call)}; Report('{name}', 'ok');")
        out.append(f"  except on E: Exception do Report('{name}', 'raised ' + E.Message); end;")
    out.append("  WriteLn('ROUTINES DONE');")
    out.append("end;")
    return "\n".join(out) + "\n"


def expected(row):
    """('ok' | 'raised', text the message must hold)."""
    name, _sig, _unit, category, st, note, _call = row
    if st == "rendering":
        return "raised", "belongs to rendering"
    if st == "missing":
        if category == "registered variable":
            return "ok", ""  # a variable cannot raise; its note says what it lacks
        return "raised", "not yet available"
    if note.startswith("raises"):
        return "raised", ""
    return "ok", ""


def expect(rows, stderr_path):
    with open(stderr_path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    seen = {}
    for m in re.finditer(r"^script: ROUTINE (\S+) (ok|raised)(.*)$", text, re.M):
        seen[m.group(1)] = (m.group(2), m.group(3).strip())
    failures = []
    if "script: ROUTINES DONE" not in text:
        failures.append("the script did not reach its end")
    for row in rows:
        name = row[0]
        want, holds = expected(row)
        if name not in seen:
            failures.append(f"{name}: no report")
            continue
        got, message = seen[name]
        if got != want or (holds and holds not in message):
            failures.append(f"{name} ({row[4]}): expected {want} {holds!r}, got {got} {message!r}")
    for f in failures:
        print(f, file=sys.stderr)
    print(f"{len(rows) - len(failures)} of {len(rows)} routines did what routines.tsv says")
    return 1 if failures else 0


# --- the documentation table ----------------------------------------------------------------

def table(rows):
    counts = {s: sum(1 for r in rows if r[4] == s) for s in STATUSES}
    simtwo = [r for r in rows if r[2] != "engine"]
    engine = [r for r in rows if r[2] == "engine"]
    lines = [BEGIN, "",
             f"{len(rows)} routines: the {len(simtwo)} SimTwo registers (routines and variables) "
             f"and the {len(engine)} built-ins of the Pascal Script engine. "
             f"**yes {counts['yes']}**, **differs {counts['differs']}**, "
             f"**rendering {counts['rendering']}** (declared, raise \"… belongs to rendering\"), "
             f"**missing {counts['missing']}** (declared, raise \"… is not yet available in "
             "S2Sim\"; a variable stays as the note says).", ""]
    categories = []
    for r in rows:
        if r[3] not in categories:
            categories.append(r[3])
    for cat in categories:
        lines += ["", f"**{cat}**", "", "| routine | S2Sim |", "|---|---|"]
        for name, signature, unit, _cat, st, note, _call in (r for r in rows if r[3] == cat):
            cell = st + (": " + note.replace("|", "\\|") if note else "")
            lines.append(f"| `{signature.replace('|', '/')}` | {cell} |")
    lines += ["", END]
    return "\n".join(lines)


def docs_text(rows):
    with open(DOCS, encoding="utf-8") as f:
        text = f.read()
    if BEGIN not in text or END not in text:
        sys.exit(f"{DOCS}: the markers of the coverage table are missing ({BEGIN} ... {END})")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return text, head + table(rows) + tail


def main(argv):
    if len(argv) < 2 or argv[1] not in ("script", "expect", "docs", "check-docs"):
        print(__doc__, file=sys.stderr)
        return 2
    rows = load()
    if argv[1] == "script":
        with open(argv[2], "w", encoding="utf-8") as f:
            f.write(script(rows))
        return 0
    if argv[1] == "expect":
        return expect(rows, argv[2])
    old, new = docs_text(rows)
    if argv[1] == "docs":
        with open(DOCS, "w", encoding="utf-8") as f:
            f.write(new)
        return 0
    if old != new:
        print(f"{DOCS}: the coverage table is stale; run scripts/script-api.py docs", file=sys.stderr)
        return 1
    print("docs/scripting.md's coverage table matches plugins/pascal_script/routines.tsv")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
