#!/usr/bin/env python3
"""The ctest suite of a build, carried to a machine without the build tree
(tools/gpu_build.sh, tools/gpu_run.sh).

    gpu_tests.py list BUILD_DIR SOURCE_DIR OUT.json
        writes the build's tests (ctest --show-only=json-v1) with their paths
        made relative: {bin} the folder of the bundled executables, {source}
        the source tree, {work} a scratch folder in place of the build tree;
        other programs (cmake, python3) are called by name from PATH.
    gpu_tests.py run TESTS.json BIN_DIR SOURCE_DIR WORK_DIR [--timeout S] [-R REGEX]
        runs them as ctest would (working directory, skip code), one line
        per test, each test's output in WORK_DIR/logs; exit status 1 if any
        failed.

Standard library only: the GPU machine runs it with whatever python3 it has."""
import argparse, json, os, re, subprocess, sys, time


def relative_command(args, build, source, executables):
    """Paths of the build's executables, the build tree and the source tree
    replaced by {bin}, {work} and {source} (the build tree may lie inside
    the source tree, so it goes first)."""
    out = []
    for k, arg in enumerate(args):
        if k == 0 and os.path.isabs(arg) and arg not in executables:
            out.append(os.path.basename(arg))
            continue
        for path, name in executables.items():
            arg = arg.replace(path, "{bin}/" + name)
        out.append(arg.replace(build, "{work}").replace(source, "{source}"))
    return out


def list_tests(build, source, out_path):
    build, source = os.path.realpath(build), os.path.realpath(source)
    info = json.loads(subprocess.run(["ctest", "--show-only=json-v1"], cwd=build, check=True,
                                     capture_output=True, text=True).stdout)
    tests = [t for t in info["tests"] if t.get("command")]
    executables = {}
    for t in tests:
        for arg in t["command"]:
            for word in arg.split("="):
                if word.startswith(build + "/") and os.access(word, os.X_OK) and os.path.isfile(word):
                    executables[word] = os.path.basename(word)
    entries = []
    for t in tests:
        properties = {p["name"]: p["value"] for p in t.get("properties", [])}
        entries.append({
            "name": t["name"],
            "command": relative_command(t["command"], build, source, executables),
            "cwd": properties.get("WORKING_DIRECTORY", build).replace(build, "{work}"),
            "skip_code": properties.get("SKIP_RETURN_CODE")})
    with open(out_path, "w") as f:
        json.dump({"executables": sorted(set(executables.values())), "tests": entries}, f, indent=1)
    for path in sorted(executables):
        print(path)


def expand(text, places):
    for key, value in places.items():
        text = text.replace("{" + key + "}", value)
    return text


def summary_lines(log):
    """The lines worth seeing without opening the log: each test program's
    closing count, skipped backends, failed checks."""
    keep = re.compile(r"passed, \d+ failed|note: backend|FAILED")
    return [line for line in log.splitlines() if keep.search(line)][-6:]


def run_tests(tests_path, bin_dir, source, work, timeout, pattern):
    with open(tests_path) as f:
        tests = json.load(f)["tests"]
    places = {"bin": os.path.realpath(bin_dir), "source": os.path.realpath(source),
              "work": os.path.realpath(work)}
    logs = os.path.join(places["work"], "logs")
    os.makedirs(logs, exist_ok=True)
    env = dict(os.environ, AMSPH_SOURCE_DIR=places["source"])
    counts = {"passed": 0, "failed": 0, "skipped": 0}
    for t in tests:
        if pattern and not re.search(pattern, t["name"]):
            continue
        command = [expand(a, places) for a in t["command"]]
        cwd = expand(t["cwd"], places)
        os.makedirs(cwd, exist_ok=True)
        start = time.time()
        try:
            p = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, errors="replace",
                               timeout=timeout)
            status, log = p.returncode, p.stdout
        except subprocess.TimeoutExpired as e:  # its output may come as bytes despite text=True
            output = e.stdout or ""
            status = "timeout"
            log = output.decode(errors="replace") if isinstance(output, bytes) else output
        except OSError as e:
            status, log = "not run", str(e)
        seconds = time.time() - start
        with open(os.path.join(logs, re.sub(r"[^A-Za-z0-9_.-]", "_", t["name"]) + ".log"), "w") as f:
            f.write(log)
        if status == 0:
            verdict = "passed"
        elif t["skip_code"] is not None and status == t["skip_code"]:
            verdict = "skipped"
        else:
            verdict = "failed"
        counts[verdict] += 1
        print(f"{verdict.upper():8s} {seconds:7.1f} s  {t['name']}"
              + ("" if verdict != "failed" else f"  (status {status})"), flush=True)
        for line in summary_lines(log) if verdict != "failed" else log.splitlines()[-30:]:
            print("         " + line)
    print(f"{counts['passed']} passed, {counts['failed']} failed, {counts['skipped']} skipped")
    return 1 if counts["failed"] else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="verb", required=True)
    p = sub.add_parser("list")
    p.add_argument("build")
    p.add_argument("source")
    p.add_argument("out")
    p = sub.add_parser("run")
    p.add_argument("tests")
    p.add_argument("bin")
    p.add_argument("source")
    p.add_argument("work")
    p.add_argument("--timeout", type=float, default=600)
    p.add_argument("-R", dest="pattern", help="run only the tests whose name matches")
    a = parser.parse_args()
    if a.verb == "list":
        list_tests(a.build, a.source, a.out)
        return 0
    return run_tests(a.tests, a.bin, a.source, a.work, a.timeout, a.pattern)


if __name__ == "__main__":
    sys.exit(main())
