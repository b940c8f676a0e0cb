#!/usr/bin/env python3
"""Runs a tutorial of docs/tutorials/ and checks what it shows (tests/docs/CMakeLists.txt).

    tutorial_test.py TUTORIAL.md PREFIX SOURCE_DIR

The tutorial's fenced blocks, in order, in a fresh folder holding links to the repository's
scenes/ and examples/, with PREFIX/bin on PATH and PREFIX as CMAKE_PREFIX_PATH (S2Sim
installed there, as the tutorials ask):
  ```xml file=PATH (any language)   written to PATH
  ```sh                             run by bash -e -o pipefail; its output is kept
  ```text output                    every line must be a line of the last sh block's output
                                    (spaces at the ends ignored; a line `...` is skipped)
Every other block is prose. Exit 0 when every command succeeds and every output is shown."""
import os
import re
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```[ \t]*$", re.M | re.S)


NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def skeleton(line):
    """A line with its numbers blanked: how an output line is recognised after physics moved."""
    return NUMBER.sub("#", " ".join(line.split()))


def main():
    # --update (after a deliberate change of physics): each shown line the output lacks is
    # replaced by the output's one line of the same words, numbers apart (for rows of numbers,
    # the one of the same first field); any other is a failure.
    update = "--update" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--update"]
    tutorial, prefix, source = args[0:3]
    text = open(tutorial, encoding="utf-8").read()
    replacements = []
    env = dict(os.environ)
    env["PATH"] = os.path.join(prefix, "bin") + os.pathsep + env.get("PATH", "")
    env["CMAKE_PREFIX_PATH"] = prefix
    env.pop("S2SIM_PLUGIN_PATH", None)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="s2sim_tutorial_") as work:
        for name in ("scenes", "examples"):
            os.symlink(os.path.join(source, name), os.path.join(work, name))
        output = None
        blocks = 0
        for match in FENCE.finditer(text):
            info, body = match.group(1).split(), match.group(2)
            line = text.count("\n", 0, match.start()) + 1
            files = [w[5:] for w in info if w.startswith("file=")]
            if files:
                path = os.path.join(work, files[0])
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w", encoding="utf-8") as f:
                    f.write(body)
                print(f"{tutorial}:{line}: wrote {files[0]}")
            elif info[:1] == ["sh"]:
                blocks += 1
                print(f"{tutorial}:{line}: $ " + body.strip().replace("\n", "\n  "))
                run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", body], cwd=work,
                                     env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True)
                output = run.stdout
                sys.stdout.write(output)
                if run.returncode != 0:
                    print(f"FAIL {tutorial}:{line}: exit status {run.returncode}")
                    return 1
            elif info[:2] == ["text", "output"]:
                if output is None:
                    print(f"FAIL {tutorial}:{line}: an output block before any command")
                    return 1
                shown = {l.strip() for l in output.splitlines()}
                for expected in body.splitlines():
                    expected = expected.strip()
                    if expected and expected != "..." and expected not in shown:
                        same = [l for l in shown if skeleton(l) == skeleton(expected)]
                        if len(same) > 1:  # a CSV row: the one of the same first field (time)
                            key = re.split(r"[,\s]", expected, maxsplit=1)[0]
                            same = [l for l in same if re.split(r"[,\s]", l, maxsplit=1)[0] == key]
                        if update and len(same) == 1:
                            replacements.append((match.start(2), match.end(2), expected, same[0]))
                            continue
                        print(f"FAIL {tutorial}:{line}: the output lacks the line: {expected}")
                        failures += 1
        if blocks == 0:
            print(f"FAIL {tutorial}: no command to run")
            return 1
    for start, end, old, new in reversed(replacements):
        block = text[start:end]
        at = block.index(old)
        text = text[:start] + block[:at] + new + block[at + len(old):] + text[end:]
    if replacements:
        open(tutorial, "w", encoding="utf-8").write(text)
        print(f"updated {len(replacements)} lines of {tutorial}")
    print("ok" if failures == 0 else f"{failures} lines not shown")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
