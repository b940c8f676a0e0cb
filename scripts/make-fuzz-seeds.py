#!/usr/bin/env python3
"""Seeds for the libFuzzer scene target (tests/fuzz/scene_fuzzer.cpp, docs/reliability.md).

Each seed is one scene folder folded into one input: its scene.xml with the first robot's
body file renamed bot.xml, a NUL byte, then that robot file. Files other than the first robot
(things.xml, tracks, other robots) are left out, so the seed loads what survives alone.

    scripts/make-fuzz-seeds.py OUT_DIR SCENE_ROOT...
"""
import pathlib
import re
import sys


def seeds(root: pathlib.Path):
    for scene in sorted(root.rglob("scene.xml")):
        text = scene.read_text(errors="replace")
        robot = b""
        match = re.search(r"<body\s+file\s*=\s*['\"]([^'\"]+)['\"]", text)
        if match and (scene.parent / match.group(1)).is_file():
            robot = (scene.parent / match.group(1)).read_bytes()
            text = text[: match.start(1)] + "bot.xml" + text[match.end(1) :]
        yield scene.parent.name, text.encode() + b"\0" + robot


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 4
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    count = 0
    for root in sys.argv[2:]:
        for name, data in seeds(pathlib.Path(root)):
            (out / f"seed-{count:03d}-{name}").write_bytes(data)
            count += 1
    print(f"{count} seeds in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
