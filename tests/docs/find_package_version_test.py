#!/usr/bin/python3
"""Every `find_package(S2Sim X.Y ...)` in the docs, the README and the examples asks for the
project's version (sdk/include/s2sim/version.hpp): an older one fails against the installed
package (SameMinorVersion), a newer one cannot be met.

    find_package_version_test.py SOURCE_DIR
"""

import pathlib
import re
import sys


def project_version(source):
    text = (source / "sdk" / "include" / "s2sim" / "version.hpp").read_text()
    major = re.search(r"#define S2SIM_SDK_VERSION_MAJOR (\d+)", text).group(1)
    minor = re.search(r"#define S2SIM_SDK_VERSION_MINOR (\d+)", text).group(1)
    return f"{major}.{minor}"


def main():
    source = pathlib.Path(sys.argv[1])
    want = project_version(source)
    files = [source / "README.md", *sorted((source / "docs").rglob("*.md")),
             *sorted((source / "examples").rglob("CMakeLists.txt"))]
    found, wrong = 0, []
    for path in files:
        for number, line in enumerate(path.read_text().splitlines(), 1):
            for version in re.findall(r"find_package\(\s*S2Sim\s+(\d+(?:\.\d+)*)", line):
                found += 1
                if ".".join(version.split(".")[:2]) != want:
                    wrong.append(f"{path.relative_to(source)}:{number}: find_package(S2Sim "
                                 f"{version}) but the project is {want}")
    if wrong:
        print("\n".join(wrong))
        return 1
    if found < 3:  # plugins.md, embedding.md and the examples at least
        print(f"only {found} versioned find_package calls found: the pattern is stale")
        return 1
    print(f"{found} find_package(S2Sim {want}) calls agree with the project version")
    return 0


if __name__ == "__main__":
    sys.exit(main())
