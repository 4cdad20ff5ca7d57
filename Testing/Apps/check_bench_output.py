"""Runs ThinTissueBench and checks that every stdout line is one JSON object
with the fields {"suite","case","metric","value","unit","thesis"}, that every
listed suite reported, and that values are finite and positive."""
import json
import math
import subprocess
import sys

FIELDS = {"suite", "case", "metric", "value", "unit", "thesis"}


def main():
    command = sys.argv[1:]
    suites = subprocess.run([command[0], "--list"], check=True, capture_output=True,
                            text=True).stdout.split("\n")
    suites = {line.split("\t")[0] for line in suites if line.strip()}
    run = subprocess.run(command, capture_output=True, text=True)
    sys.stderr.write(run.stderr)
    if run.returncode != 0:
        sys.exit("ThinTissueBench exited with %d" % run.returncode)
    lines = [line for line in run.stdout.split("\n") if line.strip()]
    if not lines:
        sys.exit("no output")
    reported = set()
    for line in lines:
        record = json.loads(line)
        if set(record) != FIELDS:
            sys.exit("wrong fields in %s" % line)
        if not isinstance(record["value"], (int, float)) or not math.isfinite(record["value"]) \
                or record["value"] <= 0:
            sys.exit("bad value in %s" % line)
        if record["thesis"] is not None and not isinstance(record["thesis"], (int, float)):
            sys.exit("bad thesis figure in %s" % line)
        reported.add(record["suite"])
    if reported != suites:
        sys.exit("suites %s listed but %s reported" % (sorted(suites), sorted(reported)))
    print("%d JSON lines from suites %s" % (len(lines), ", ".join(sorted(reported))))


if __name__ == "__main__":
    main()
