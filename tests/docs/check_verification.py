#!/usr/bin/python3
"""docs/verification.md names every test suite, so that a new suite cannot go undocumented.

    check_verification.py REPOSITORY

The suites are the first argument of every TEST(, TEST_F( and TEST_P( in tests/unit/*.cpp and
tests/hard/*.cpp (GoogleTest suite names), and every python/tests/test_*.py file. Each must
appear in docs/verification.md as a whole word, in backticks or plain, with its exact case
(`Periodic` or Periodic for the suite Periodic; `test_study.py` for python/tests/test_study.py).
Exits 0 when every one does, 1 naming each one that does not and the file that defines it.
"""
import glob
import os
import re
import sys

SUITE = re.compile(r"\bTEST(?:_F|_P)?\s*\(\s*([A-Za-z_][A-Za-z0-9_]*)\s*,")


def suites(repository):
    """{suite name: [files that define it]} for the GoogleTest sources."""
    found = {}
    for directory in ("tests/unit", "tests/hard"):
        for path in sorted(glob.glob(os.path.join(repository, directory, "*.cpp"))):
            with open(path, encoding="utf-8") as source:
                text = source.read()
            for name in SUITE.findall(text):
                files = found.setdefault(name, [])
                relative = os.path.relpath(path, repository)
                if relative not in files:
                    files.append(relative)
    return found


def python_tests(repository):
    """{file name: [its path]} for the Python module's test files."""
    return {
        os.path.basename(path): [os.path.relpath(path, repository)]
        for path in sorted(glob.glob(os.path.join(repository, "python/tests/test_*.py")))
    }


def mentioned(name, text):
    return re.search(r"(?<![A-Za-z0-9_])" + re.escape(name) + r"(?![A-Za-z0-9_])", text) is not None


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    repository = sys.argv[1]
    document = os.path.join(repository, "docs", "verification.md")
    try:
        with open(document, encoding="utf-8") as page:
            text = page.read()
    except OSError as error:
        print(f"check_verification: cannot read {document}: {error.strerror}")
        return 1
    expected = suites(repository)
    expected.update(python_tests(repository))
    if len(expected) < 10:
        print(f"check_verification: found only {len(expected)} suites under {repository}: "
              "is that the repository?")
        return 1
    missing = {name: files for name, files in expected.items() if not mentioned(name, text)}
    for name in sorted(missing):
        print(f"docs/verification.md does not mention {name} ({', '.join(missing[name])})")
    if missing:
        print(f"check_verification: {len(missing)} of {len(expected)} suites and test files "
              "are not in docs/verification.md; add a row for each")
        return 1
    print(f"check_verification: docs/verification.md mentions all {len(expected)} suites and "
          "test files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
