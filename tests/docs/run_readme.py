#!/usr/bin/python3
"""Runs the README's code blocks as a newcomer would, so that the documentation cannot rot.

    run_readme.py REPOSITORY BUILD_DIR [MARKDOWN]

In a scratch directory that holds `build` (a link to BUILD_DIR) and `netlists` (a link to the
repository's scenes), the blocks of MARKDOWN (default: the README) are taken in order:

- a ```toml or ```python block after `<!-- file: NAME -->` is appended to the file NAME (the
  tutorial starts its scene from an empty file and adds to it block by block);
- a ```sh block is run with bash (-e, -o pipefail); its exit status must be 0, or N after
  `<!-- exit: N -->`; every file it names after --plot, --csv or -o must then exist and not be
  empty (a .png must be a PNG);
- a ```text block right after a ```sh block is an excerpt of that block's output: each of its
  lines must appear in the output, in order, where "…" stands for any text and runs of spaces
  match any run of spaces;
- a block after `<!-- not run: REASON -->` is skipped; any other block that is not sh, toml,
  python or text is an error, so that nothing is shown that is not run.

When the tutorial wrote finger.toml, its network must be the one of netlists/gripper-finger.toml
(the scene the tutorial teaches): the same first three modes to 1e-12 relative (the same network
assembled twice: any difference is rounding of the eigen-solver), the same AC response of the tip
to 1e-12 of its peak (the same reasoning for a direct complex solve) and the same IDA time
response of the tip to 1e-5 of its peak (IDA's rtol is 1e-6; equal networks take equal steps, and
a margin of 10 allows the step sequence to differ by rounding).

Exits 0 when every block ran as shown, 1 otherwise, naming the README line of each failure.
"""
import cmath
import json
import math
import os
import re
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^```(\w*)\s*$")
MARKER = re.compile(r"^<!--\s*(file|exit|not run):?\s*(.*?)\s*-->\s*$")
OUTPUT_FILE_OPTIONS = ("--plot", "--csv", "-o")
BLOCK_TIMEOUT_SECONDS = 300


def blocks_of(markdown_lines):
    """Yields (line number, language, text, markers) for each fenced block."""
    markers = {}
    number = 0
    while number < len(markdown_lines):
        line = markdown_lines[number]
        marker = MARKER.match(line)
        fence = FENCE.match(line)
        if marker:
            markers[marker.group(1)] = marker.group(2)
        elif fence:
            start = number + 1
            body = []
            number += 1
            while number < len(markdown_lines) and not markdown_lines[number].startswith("```"):
                body.append(markdown_lines[number])
                number += 1
            if number == len(markdown_lines):
                raise SystemExit(f"README:{start}: a code block is not closed")
            yield start, fence.group(1), "\n".join(body) + "\n", markers
            markers = {}
        elif line.strip():
            markers = {}
        number += 1


def normalised(text):
    return " ".join(text.split())


def excerpt_pattern(line):
    parts = [re.escape(normalised(part)) for part in line.split("…")]
    return re.compile(r"\s*.*?\s*".join(parts))


def check_excerpt(excerpt, output):
    """Returns the first excerpt line not found (in order) in the output, or None."""
    output_lines = [normalised(line) for line in output.splitlines()]
    position = 0
    for line in excerpt.splitlines():
        if not line.strip():
            continue
        pattern = excerpt_pattern(line)
        while position < len(output_lines) and not pattern.fullmatch(output_lines[position]):
            position += 1
        if position == len(output_lines):
            return line
        position += 1
    return None


def named_output_files(script):
    words = script.replace("\\\n", " ").split()
    return [words[i + 1] for i, word in enumerate(words[:-1]) if word in OUTPUT_FILE_OPTIONS]


def file_problem(path):
    if not os.path.isfile(path):
        return "was not written"
    if os.path.getsize(path) == 0:
        return "is empty"
    if path.endswith(".png"):
        with open(path, "rb") as image:
            if image.read(8) != b"\x89PNG\r\n\x1a\n":
                return "is not a PNG"
    return None


def run(command, scratch):
    return subprocess.run(command, cwd=scratch, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=BLOCK_TIMEOUT_SECONDS)


def json_of(command, scratch):
    finished = run(command, scratch)
    if finished.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {finished.returncode}:\n{finished.stdout}")
    return json.loads(finished.stdout)


def peak_relative_difference(values, references):
    peak = max(abs(value) for value in references)
    return max(abs(a - b) for a, b in zip(values, references)) / peak


def compare_with_shipped(scratch, failures):
    """The tutorial's finger against netlists/gripper-finger.toml: the same network."""
    tutorial, shipped = "finger.toml", "netlists/gripper-finger.toml"
    emnet = os.path.join("build", "emnet")

    def modes(scene):
        result = json_of([emnet, "modes", scene, "--count", "3", "--json"], scratch)
        return [mode["frequency_hz"] for mode in result["modes"]]

    def tip_ac(scene):
        result = json_of([emnet, "ac", scene, "--probe", "tip", "--from", "1", "--to", "200",
                          "--points", "41", "--scale", "log", "--json"], scratch)
        probe = next(probe for probe in result["probes"] if probe["name"] == "tip")
        return [cmath.rect(magnitude, math.radians(phase))
                for magnitude, phase in zip(probe["magnitude"], probe["phase_deg"])]

    def tip_tran(scene):
        result = json_of([emnet, "tran", scene, "--periods", "2", "--probe", "tip", "--json"],
                         scratch)
        return next(output for output in result["outputs"] if output["name"] == "tip")["values"]

    checks = [("first three modes [Hz]", modes, 1e-12, "relative"),
              ("AC response of the tip", tip_ac, 1e-12, "of the peak"),
              ("IDA time response of the tip", tip_tran, 1e-5, "of the peak")]
    for what, compute, tolerance, relative_to in checks:
        try:
            ours, theirs = compute(tutorial), compute(shipped)
        except (RuntimeError, KeyError, StopIteration, ValueError) as error:
            failures.append(f"comparing the tutorial's {what} with {shipped}: {error}")
            continue
        if len(ours) != len(theirs) or not ours:
            failures.append(f"{what}: {len(ours)} values from the tutorial, {len(theirs)} "
                            f"from {shipped}")
            continue
        if relative_to == "relative":
            difference = max(abs(a - b) / abs(b) for a, b in zip(ours, theirs))
        else:
            difference = peak_relative_difference(ours, theirs)
        verdict = "ok" if difference <= tolerance else "DIFFERS"
        print(f"tutorial against {shipped}: {what}: {difference:.2e} {relative_to} "
              f"(tolerance {tolerance:g}) {verdict}")
        if difference > tolerance:
            failures.append(f"the tutorial's {what} differs from {shipped} by {difference:.2e}")


def main():
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    repository, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    markdown = sys.argv[3] if len(sys.argv) == 4 else os.path.join(repository, "README.md")
    with open(markdown, encoding="utf-8") as file:
        lines = file.read().splitlines()

    failures = []
    with tempfile.TemporaryDirectory(prefix="emnet-readme-") as scratch:
        os.symlink(build, os.path.join(scratch, "build"))
        os.symlink(os.path.join(repository, "netlists"), os.path.join(scratch, "netlists"))
        last_output = None
        ran = 0
        for line, language, text, markers in blocks_of(lines):
            where = f"{os.path.basename(markdown)}:{line}"
            if "not run" in markers:
                last_output = None
                continue
            if language in ("toml", "python") and "file" in markers:
                with open(os.path.join(scratch, markers["file"]), "a", encoding="utf-8") as file:
                    file.write(("\n" if file.tell() else "") + text)
                last_output = None
            elif language == "sh":
                expected_status = int(markers.get("exit", "0"))
                finished = run(["bash", "-e", "-o", "pipefail", "-c", text], scratch)
                ran += 1
                last_output = finished.stdout
                print(f"{where}: {text.strip().splitlines()[0]} -> exit {finished.returncode}")
                if finished.returncode != expected_status:
                    failures.append(f"{where}: exit status {finished.returncode}, expected "
                                    f"{expected_status}; output:\n{finished.stdout}")
                for path in named_output_files(text):
                    problem = file_problem(os.path.join(scratch, path))
                    if problem:
                        failures.append(f"{where}: {path} {problem}")
            elif language == "text" and last_output is not None:
                missing = check_excerpt(text, last_output)
                if missing is not None:
                    failures.append(f"{where}: this line of the shown output is not in the "
                                    f"output (in order):\n  {missing}\nthe output was:\n"
                                    f"{last_output}")
                last_output = None
            else:
                failures.append(f"{where}: a ```{language} block that is neither run nor marked "
                                "<!-- not run: why --> (a toml or python block needs "
                                "<!-- file: NAME -->; a text block follows a sh block)")
        if os.path.exists(os.path.join(scratch, "finger.toml")):
            compare_with_shipped(scratch, failures)
        print(f"{ran} command blocks run")

    for failure in failures:
        print(f"FAILED: {failure}", file=sys.stderr)
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
