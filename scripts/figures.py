#!/usr/bin/python3
"""Reruns the headline figures README.md and docs/*.md state and holds each against the docs.

The manifest (scripts/figures.yaml) lists runs (a command each, run from the repository root)
and figures. A figure names the doc and a regular expression that reads its DOCUMENTED value
out of the doc text (never a copy of the number: the docs and this check cannot drift apart),
the run whose output holds the MEASURED value and a regular expression that reads it, the
figure's noise (tolerance) and, optionally, a target the measured value must meet.

  figures.py [--quick] [--only ID[,ID...]] [--rooms DIR] [--build DIR] [--logs DIR]
  figures.py --list [--quick] [--only ...]      the manifest, with each documented value, no runs
  figures.py --check-manifest [--build DIR]     the manifest's self-check (a ctest): every doc
                                                pattern found once, every command a built tool
                                                taking the options given
Options:
  --quick          only the runs marked quick (each under about 2 minutes on two cores)
  --only ID,...    only these figures (shell-style patterns: 'ranging.*')
  --rooms DIR      the measured rooms (default ../shared/realrooms, where the docs put them)
  --build DIR      the build folder the commands' tools are in (default build)
  --logs DIR       where each run's output is kept (default a new folder under /tmp)
  --manifest FILE  another manifest (default scripts/figures.yaml beside this script)
  --root DIR       the repository root (default this script's folder's parent)

One line per figure: id, documented, measured, tolerance, and OK, MOVED (beyond its tolerance),
TARGET MISSED, FAILED (the command failed or a pattern found nothing) or SKIPPED (a file the run
needs is missing, e.g. the thesis's map); the runs' commands above their figures; a summary.
Exit status 1 if any figure moved, missed its target or failed; 2 for a bad manifest or option.
"""
import argparse
import datetime
import fnmatch
import os
import pathlib
import re
import shlex
import subprocess
import sys
import time

import yaml

# A number as the docs and the tools write it: a sign, digits, a decimal part (no exponent).
NUM = r"([-+]?\d+(?:\.\d+)?)"
TARGET = re.compile(r"^\s*(<=|>=|<|>|==)\s*([-+]?\d+(?:\.\d+)?)\s*$")
VARIABLE = re.compile(r"\{([a-z_]+)\}")
FIGURE_KEYS = {"id", "doc", "documented", "run", "measured", "tolerance", "target", "unit", "abs"}
RUN_KEYS = {"command", "quick", "minutes", "requires"}


class ManifestError(Exception):
    """The manifest or an option is wrong; the message names the entry and the field."""


def expand_num(pattern):
    """Patterns write {num} for a number; the rest is a Python regular expression."""
    return pattern.replace("{num}", NUM)


def squeeze(text):
    """Docs wrap their lines anywhere: patterns are matched against text whose whitespace runs
    are single spaces, so a rewrapped paragraph still matches."""
    return re.sub(r"\s+", " ", text)


def parse_number(text, what):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise ManifestError(f"{what}: expected a number, got '{text}'")


def parse_tolerance(value, fid):
    """A number is absolute (in the figure's unit); 'N%' is relative to the documented value."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value >= 0:
        return float(value), False
    if isinstance(value, str) and re.fullmatch(r"\d+(\.\d+)?%", value.strip()):
        return float(value.strip()[:-1]) / 100.0, True
    raise ManifestError(f"{fid}: tolerance: expected a number >= 0 or 'N%', got '{value}'")


def parse_target(value, fid):
    match = TARGET.match(str(value))
    if not match:
        raise ManifestError(f"{fid}: target: expected '<= N', '>= N', '< N', '> N' or '== N', got '{value}'")
    return match.group(1), float(match.group(2))


def meets(value, target):
    op, bound = target
    return {"<=": value <= bound, ">=": value >= bound, "<": value < bound, ">": value > bound,
            "==": value == bound}[op]


def load_manifest(path):
    try:
        data = yaml.safe_load(pathlib.Path(path).read_text())
    except OSError as error:
        raise ManifestError(f"{path}: cannot read it ({error.strerror})")
    except yaml.YAMLError as error:
        raise ManifestError(f"{path}: not YAML: {error}")
    if not isinstance(data, dict) or not isinstance(data.get("runs"), dict) or not isinstance(data.get("figures"), list):
        raise ManifestError(f"{path}: expected 'variables', 'runs' (a mapping) and 'figures' (a list)")
    variables = data.get("variables") or {}
    runs = data["runs"]
    for name, run in runs.items():
        if not isinstance(run, dict) or not isinstance(run.get("command"), str):
            raise ManifestError(f"run {name}: expected a mapping with a 'command'")
        unknown = set(run) - RUN_KEYS
        if unknown:
            raise ManifestError(f"run {name}: unknown fields {sorted(unknown)} (known: {sorted(RUN_KEYS)})")
        if not isinstance(run.get("minutes", 1), (int, float)):
            raise ManifestError(f"run {name}: minutes: expected a number")
        for word in VARIABLE.findall(run["command"] + " ".join(run.get("requires", []))):
            if word not in variables and word != "out":
                raise ManifestError(f"run {name}: {{{word}}} is no variable (known: {sorted(variables)})")
    seen = set()
    figures = []
    for entry in data["figures"]:
        fid = entry.get("id") if isinstance(entry, dict) else None
        if not isinstance(fid, str):
            raise ManifestError(f"figure {entry!r}: expected a mapping with an 'id'")
        if fid in seen:
            raise ManifestError(f"{fid}: id given twice")
        seen.add(fid)
        unknown = set(entry) - FIGURE_KEYS
        if unknown:
            raise ManifestError(f"{fid}: unknown fields {sorted(unknown)} (known: {sorted(FIGURE_KEYS)})")
        for field in ("doc", "documented", "run", "measured", "tolerance"):
            if field not in entry:
                raise ManifestError(f"{fid}: '{field}' missing")
        if entry["run"] not in runs:
            raise ManifestError(f"{fid}: run '{entry['run']}' is not among the runs")
        figure = dict(entry)
        figure["tolerance"] = parse_tolerance(entry["tolerance"], fid)
        figure["target"] = parse_target(entry["target"], fid) if "target" in entry else None
        for field in ("documented", "measured"):
            try:
                compiled = re.compile(expand_num(entry[field]), re.M)
            except re.error as error:
                raise ManifestError(f"{fid}: {field}: not a regular expression: {error}")
            if compiled.groups != 1:
                raise ManifestError(f"{fid}: {field}: expected one group (the number), found {compiled.groups}")
            figure[field + "_re"] = compiled
        figures.append(figure)
    return variables, runs, figures


def substitute(text, variables, out="{out}"):
    """Puts the variables into a command; {out} is the run's own scratch folder."""
    return VARIABLE.sub(lambda m: out if m.group(1) == "out" else str(variables[m.group(1)]), text)


def documented_value(figure, root, docs_cache):
    """The documented figure, read from the doc text; the pattern must match exactly once."""
    doc = figure["doc"]
    if doc not in docs_cache:
        try:
            docs_cache[doc] = squeeze((root / doc).read_text())
        except OSError:
            raise ManifestError(f"{figure['id']}: doc {doc} not found")
    matches = list(figure["documented_re"].finditer(docs_cache[doc]))
    if len(matches) != 1:
        raise ManifestError(f"{figure['id']}: documented pattern found {len(matches)} times in {doc}, expected once: "
                            f"{figure['documented']}")
    value = parse_number(matches[0].group(1), f"{figure['id']}: documented value in {doc}")
    return abs(value) if figure.get("abs") else value


def measured_value(figure, output):
    """The first match in the run's output (the tools print each summary once)."""
    match = figure["measured_re"].search(output)
    if not match:
        return None
    value = parse_number(match.group(1), f"{figure['id']}: measured value")
    return abs(value) if figure.get("abs") else value


def tolerance_text(figure, documented):
    amount, relative = figure["tolerance"]
    unit = figure.get("unit", "")
    if relative:
        return f"{amount * 100:g}% (+-{amount * abs(documented):.3g}{unit})"
    return f"+-{amount:g}{unit}"


def judge(figure, documented, measured):
    """The statuses of one figure: OK, or MOVED and/or TARGET MISSED."""
    amount, relative = figure["tolerance"]
    allowed = amount * abs(documented) if relative else amount
    statuses = []
    # A hair of slack for floating point: 0.3 against 0.1 with +-0.2 is within.
    if abs(measured - documented) > allowed + 1e-9:
        statuses.append("MOVED")
    if figure["target"] and not meets(measured, figure["target"]):
        statuses.append("TARGET MISSED")
    return statuses or ["OK"]


def select(figures, runs, options):
    chosen = figures
    if options.only:
        patterns = [p for p in options.only.split(",") if p]
        chosen = [f for f in chosen if any(fnmatch.fnmatchcase(f["id"], p) for p in patterns)]
        if not chosen:
            raise ManifestError(f"--only {options.only}: no figure has such an id (--list shows them)")
    if options.quick:
        chosen = [f for f in chosen if runs[f["run"]].get("quick")]
    return chosen


def grouped(figures):
    """Figures by run, in the manifest's order of first appearance."""
    order = []
    for figure in figures:
        if figure["run"] not in order:
            order.append(figure["run"])
    return [(run, [f for f in figures if f["run"] == run]) for run in order]


def fmt(value, unit=""):
    return "-" if value is None else f"{value:g}{unit}"


def print_row(fid, documented, measured, tolerance, status, unit):
    print(f"  {fid:<44} {fmt(documented, unit):>12} {fmt(measured, unit):>12}  {tolerance:<22} {status}")


def list_manifest(figures, runs, variables, root):
    """Prints the manifest with each documented value; 1 if a documented value is not found."""
    docs = {}
    problems = []
    total = 0.0
    for run_name, members in grouped(figures):
        run = runs[run_name]
        total += run.get("minutes", 0)
        flag = "quick" if run.get("quick") else "full "
        print(f"[{flag} ~{run.get('minutes', '?')} min] {substitute(run['command'], variables)}")
        for figure in members:
            target = " ".join([figure["target"][0], f"{figure['target'][1]:g}"]) if figure["target"] else ""
            try:
                documented = documented_value(figure, root, docs)
            except ManifestError as error:
                problems.append(str(error))
                print(f"  {figure['id']:<44} {'NOT FOUND':>12}  {'':<22} {target:<8} {figure['doc']}")
                continue
            print(f"  {figure['id']:<44} {fmt(documented, figure.get('unit', '')):>12}  "
                  f"{tolerance_text(figure, documented):<22} {target:<8} {figure['doc']}")
    print(f"{len(figures)} figures from {len(grouped(figures))} runs, about {total:g} min on two cores")
    for problem in problems:
        print(f"figures: {problem}", file=sys.stderr)
    return 1 if problems else 0


def run_command(name, run, variables, root, logs):
    """Runs one command from the repository root; returns (output, error or None, seconds)."""
    scratch = logs / name
    command = substitute(run["command"], variables, str(scratch))
    missing = [substitute(p, variables) for p in run.get("requires", [])
               if not (root / substitute(p, variables)).exists()]
    if missing:
        return None, "SKIPPED: missing " + ", ".join(missing), 0.0
    if "{out}" in run["command"]:
        scratch.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    log = logs / f"{name}.log"
    try:
        # No shell: the manifest's commands are words. The timeout stops a hung run, not a slow
        # one: on two cores shared with other benchmarks the survey's 1.9 min took over 10.
        result = subprocess.run(shlex.split(command), cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                timeout=max(1800, 600 * run.get("minutes", 1)), text=True, errors="replace")
    except FileNotFoundError:
        return None, f"FAILED: {shlex.split(command)[0]} not found (build it, or give --build)", 0.0
    except subprocess.TimeoutExpired as error:
        output = error.stdout or ""
        log.write_text(output if isinstance(output, str) else output.decode(errors="replace"))
        return None, f"FAILED: timed out after {error.timeout:g} s (log {log})", time.monotonic() - start
    seconds = time.monotonic() - start
    log.write_text(result.stdout)
    if result.returncode != 0:
        return result.stdout, f"FAILED: exit status {result.returncode} (log {log})", seconds
    return result.stdout, None, seconds


def run_figures(figures, runs, variables, root, logs):
    docs = {}
    counts = {}
    bad = []
    print(f"figures: {len(figures)} figures from {len(grouped(figures))} runs; outputs in {logs}")
    print(f"  {'id':<44} {'documented':>12} {'measured':>12}  {'tolerance':<22} status")
    for run_name, members in grouped(figures):
        run = runs[run_name]
        print(f"$ {substitute(run['command'], variables, str(logs / run_name))}", flush=True)
        output, error, seconds = run_command(run_name, run, variables, root, logs)
        if seconds:
            print(f"  ({seconds:.0f} s)")
        for figure in members:
            unit = figure.get("unit", "")
            documented = documented_value(figure, root, docs)
            tolerance = tolerance_text(figure, documented)
            measured = measured_value(figure, output) if output is not None else None
            if error and error.startswith("SKIPPED"):
                statuses, note = ["SKIPPED"], error[len("SKIPPED: "):]
            elif error:
                statuses, note = ["FAILED"], error[len("FAILED: "):]
            elif measured is None:
                statuses, note = ["FAILED"], f"measured pattern not found in the output: {figure['measured']}"
            else:
                statuses, note = judge(figure, documented, measured), ""
                if "TARGET MISSED" in statuses:
                    note = f"target {figure['target'][0]} {figure['target'][1]:g}{unit}"
            status = ", ".join(statuses) + (f" ({note})" if note else "")
            print_row(figure["id"], documented, measured, tolerance, status, unit)
            for s in statuses:
                counts[s] = counts.get(s, 0) + 1
            if any(s in ("MOVED", "TARGET MISSED", "FAILED") for s in statuses):
                bad.append(figure["id"])
        sys.stdout.flush()
    summary = ", ".join(f"{counts[s]} {s}" for s in ("OK", "MOVED", "TARGET MISSED", "FAILED", "SKIPPED") if s in counts)
    print(f"figures: {len(figures)} checked: {summary}")
    if bad:
        print("figures: not as documented: " + ", ".join(bad))
    return 1 if bad else 0


# --- the manifest's self-check ------------------------------------------------------------------

def check_manifest(figures, runs, variables, root, build):
    """Every problem the manifest has, as lines; empty when it holds."""
    problems = []
    docs = {}
    for figure in figures:
        try:
            documented_value(figure, root, docs)
        except ManifestError as error:
            problems.append(str(error))
        if figure.get("target") and not figure["doc"]:
            problems.append(f"{figure['id']}: a target without a doc")
    used = {f["run"] for f in figures}
    for name in runs:
        if name not in used:
            problems.append(f"run {name}: no figure reads it")
    helps = {}
    for name, run in runs.items():
        words = shlex.split(run["command"])
        program = words[0]
        if program.startswith("{build}/"):
            path = pathlib.Path(build) / program[len("{build}/"):]
            if not path.is_absolute():
                path = root / path
        elif program.startswith("scripts/"):
            path = root / program
        else:
            problems.append(f"run {name}: {program}: expected a tool under {{build}}/ or a script under scripts/")
            continue
        if not os.access(path, os.X_OK):
            problems.append(f"run {name}: {path}: no such tool built (a wrong name, or not built yet)")
            continue
        if path not in helps:
            result = subprocess.run([str(path), "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                    text=True, errors="replace", timeout=60)
            helps[path] = result.stdout
        for flag in {w.split("=")[0] for w in words[1:] if re.match(r"--[a-z]", w)}:
            if not re.search(re.escape(flag) + r"(?![a-z-])", helps[path]):
                problems.append(f"run {name}: {flag}: not among {path.name}'s options (its --help)")
    return problems


def main(argv):
    here = pathlib.Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--check-manifest", action="store_true")
    parser.add_argument("--rooms")
    parser.add_argument("--build")
    parser.add_argument("--logs")
    parser.add_argument("--manifest", default=str(here / "figures.yaml"))
    parser.add_argument("--root", default=str(here.parent))
    options = parser.parse_args(argv)
    root = pathlib.Path(options.root).resolve()
    try:
        variables, runs, figures = load_manifest(options.manifest)
        if options.rooms:
            # Given on the command line: relative to where the user is, not to the repository.
            variables["rooms"] = str(pathlib.Path(options.rooms).resolve())
        if options.build:
            variables["build"] = options.build
        if options.check_manifest:
            problems = check_manifest(figures, runs, variables, root, variables.get("build", "build"))
            for problem in problems:
                print(f"figures manifest: {problem}", file=sys.stderr)
            if problems:
                return 1
            print(f"figures manifest: {len(figures)} figures, {len(runs)} runs: every documented value found "
                  "once, every command a built tool taking its options")
            return 0
        chosen = select(figures, runs, options)
        if options.list:
            return list_manifest(chosen, runs, variables, root)
        needs_rooms = any("{rooms}" in runs[f["run"]]["command"] for f in chosen)
        if needs_rooms and not (root / substitute(str(variables.get("rooms", "")), variables)).is_dir():
            raise ManifestError(f"--rooms {variables.get('rooms')}: no such folder (the measured rooms; "
                                "the docs put them in ../shared/realrooms)")
        logs = pathlib.Path(options.logs or f"/tmp/figures-{datetime.datetime.now():%Y%m%d-%H%M%S}")
        logs.mkdir(parents=True, exist_ok=True)
        return run_figures(chosen, runs, variables, root, logs)
    except ManifestError as error:
        print(f"figures: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
