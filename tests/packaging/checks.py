"""The packaging tests' verdict lines: `ok: ...` for each check that holds, `FAIL: ...` and exit 1
at the first that does not."""
import sys


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print("ok: " + message)
