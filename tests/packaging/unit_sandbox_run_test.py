#!/usr/bin/python3
"""The built wavebenchd runs under the packaged unit's sandbox (issue #22, item 13), as far as it
can be rebuilt without systemd as PID 1: the unit's SystemCallFilter= (expanded by
systemd-analyze syscall-filter) with its SystemCallErrorNumber=, its RestrictAddressFamilies=,
MemoryDenyWriteExecute= (the kernel's PR_SET_MDWE), NoNewPrivileges=, an empty capability
bounding set, LimitRTPRIO=/LimitMEMLOCK= and UMask=, as an unprivileged user when run as root.
A probe shows the sandbox bites (a packet socket and W+X memory refused); then the daemon, on the
simulated bench with the real clock, gets SCHED_FIFO and locked memory from the limits alone,
serves /api/status, records a static run with its results and stops cleanly on SIGTERM.

Usage: unit_sandbox_run_test.py SOURCE_DIR WORK_DIR WAVEBENCHD
"""
import ctypes
import errno
import glob
import http.client
import json
import os
import pwd
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

import seccomp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import packaged_unit  # noqa: E402

PR_CAPBSET_DROP = 24
PR_SET_MDWE = 65
PR_MDWE_REFUSE_EXEC_GAIN = 1


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print("ok: " + message)


def syscall_groups():
    """@group -> its entries (syscalls and @groups), from this systemd's own tables."""
    text = subprocess.run(["systemd-analyze", "syscall-filter", "--no-pager"], check=True,
                          capture_output=True, text=True).stdout
    groups, current = {}, None
    for raw in text.splitlines():
        line = raw.strip()
        if raw.startswith("@"):  # a group's name is not indented, its entries are
            current = groups.setdefault(line, [])
        elif current is not None and line and not line.startswith("#"):
            current.append(line)
    return groups


def expand(entry, groups, seen=None):
    seen = seen or set()
    if not entry.startswith("@"):
        return {entry}
    if entry in seen:
        return set()
    seen.add(entry)
    out = set()
    for e in groups[entry]:
        out |= expand(e, groups, seen)
    return out


def allowed_syscalls(unit):
    """SystemCallFilter= lines in order: the first allow list starts the set, `~` lines take
    away, later plain lines add (systemd.exec(5))."""
    groups = syscall_groups()
    allowed = None
    for value in packaged_unit.values(unit, "SystemCallFilter"):
        deny = value.startswith("~")
        names = set()
        for entry in value.lstrip("~").split():
            names |= expand(entry, groups)
        if allowed is None:
            check(not deny, "the unit's system call filter is an allow list")
            allowed = names
        elif deny:
            allowed -= names
        else:
            allowed |= names
    return allowed


def sandbox(unit, user):
    allowed = allowed_syscalls(unit)
    families = [getattr(__import__("socket"), f)
                for f in packaged_unit.values(unit, "RestrictAddressFamilies")[-1].split()]
    error = getattr(errno, packaged_unit.values(unit, "SystemCallErrorNumber")[-1])
    check(packaged_unit.values(unit, "CapabilityBoundingSet") == [""], "no capability kept")
    check(packaged_unit.values(unit, "NoNewPrivileges") == ["yes"] and
          packaged_unit.values(unit, "MemoryDenyWriteExecute") == ["yes"],
          "NoNewPrivileges and MemoryDenyWriteExecute")
    rtprio = int(packaged_unit.values(unit, "LimitRTPRIO")[-1])
    memlock = packaged_unit.values(unit, "LimitMEMLOCK")[-1]
    memlock = resource.RLIM_INFINITY if memlock == "infinity" else int(memlock)
    umask = int(packaged_unit.values(unit, "UMask")[-1], 8)
    print(f"sandbox: {len(allowed)} system calls allowed, families {families}, "
          f"errno {error}, RTPRIO {rtprio}")
    libc = ctypes.CDLL(None, use_errno=True)

    def grantable(limit, wanted):
        """The unit's limit, or this machine's hard limit where it is lower and cannot be
        raised (a container without CAP_SYS_RESOURCE)."""
        hard = resource.getrlimit(limit)[1]
        try:
            resource.setrlimit(limit, (resource.getrlimit(limit)[0], wanted))
            return wanted
        except (ValueError, OSError):
            return hard

    rtprio = grantable(resource.RLIMIT_RTPRIO, rtprio)
    memlock = grantable(resource.RLIMIT_MEMLOCK, memlock)
    limits_as_unit = (rtprio, memlock) == (int(packaged_unit.values(unit, "LimitRTPRIO")[-1]),
                                          resource.RLIM_INFINITY)
    print(f"limits: RTPRIO {rtprio}, MEMLOCK {memlock}" +
          ("" if limits_as_unit else " (this machine cannot grant the unit's limits)"))

    def enter():
        resource.setrlimit(resource.RLIMIT_RTPRIO, (rtprio, rtprio))
        resource.setrlimit(resource.RLIMIT_MEMLOCK, (memlock, memlock))
        os.umask(umask)
        if os.getuid() == 0:
            for cap in range(64):
                libc.prctl(PR_CAPBSET_DROP, cap, 0, 0, 0)
            os.setgroups([])
            os.setgid(user.pw_gid)
            os.setuid(user.pw_uid)
        if libc.prctl(PR_SET_MDWE, PR_MDWE_REFUSE_EXEC_GAIN, 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), "PR_SET_MDWE")
        f = seccomp.SyscallFilter(defaction=seccomp.ERRNO(error))
        for name in allowed - {"socket"}:
            try:
                f.add_rule(seccomp.ALLOW, name)
            except (RuntimeError, ValueError):
                pass  # a name this kernel or architecture does not have
        for family in families:
            f.add_rule(seccomp.ALLOW, "socket", seccomp.Arg(0, seccomp.EQ, family))
        f.load()  # with no_new_privs set, as libseccomp does by default

    return enter, limits_as_unit


PROBE = r"""
import errno, mmap, socket, sys
refused = []
try:
    socket.socket(socket.AF_PACKET, socket.SOCK_RAW)
except OSError:
    refused.append("AF_PACKET")
try:
    mmap.mmap(-1, 4096, prot=mmap.PROT_READ | mmap.PROT_WRITE | mmap.PROT_EXEC)
except OSError:
    refused.append("W+X")
try:
    socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    can = "CAN:open"
except OSError as e:
    can = "CAN:" + errno.errorcode[e.errno]  # EAFNOSUPPORT: a kernel without SocketCAN
print(" ".join(refused), can)
"""


def get(port, path):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=20)
    connection.request("GET", path)
    response = connection.getresponse()
    body = response.read()
    connection.close()
    return response.status, body


def real_clock_sim_config(source_dir, work):
    """The shipped configs, copied, with sim.yaml on the real clock (the bench thread asks for
    real-time scheduling only there)."""
    configs = os.path.join(work, "configs")
    shutil.copytree(os.path.join(source_dir, "configs"), configs)
    path = os.path.join(configs, "benches", "sim.yaml")
    text = open(path).read()
    check("clock: simulated" in text, "sim.yaml names its clock")
    open(path, "w").write(text.replace("clock: simulated", "clock: real"))
    return path


def main():
    source_dir, work, daemon = sys.argv[1], sys.argv[2], os.path.abspath(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    unit = packaged_unit.write_unit(source_dir, "/usr", os.path.join(work, "unit"))
    user = pwd.getpwnam("nobody")
    if os.getuid() == 0:
        os.chown(work, user.pw_uid, user.pw_gid)
    enter, limits_as_unit = sandbox(unit, user)

    probe = subprocess.run(["/usr/bin/python3", "-c", PROBE], preexec_fn=enter,
                           capture_output=True, text=True)
    words = probe.stdout.split()
    check(probe.returncode == 0 and words[:2] == ["AF_PACKET", "W+X"] and
          words[2] in ("CAN:open", "CAN:EAFNOSUPPORT"),
          f"in the sandbox a packet socket and W+X memory are refused, a CAN socket is not "
          f"({probe.stdout.strip()!r} {probe.stderr.strip()[-300:]})")

    config = real_clock_sim_config(source_dir, work)
    runs, token = os.path.join(work, "runs"), os.path.join(work, "daemon.token")
    log_path = os.path.join(work, "wavebenchd.err")
    log = open(log_path, "w+")
    process = subprocess.Popen([daemon, "--config", config, "--listen", "127.0.0.1:0",
                                "--runs", runs, "--token-file", token,
                                "--log-dir", os.path.join(work, "log")],
                               stdout=subprocess.PIPE, stderr=log, text=True, cwd=work,
                               preexec_fn=enter)
    try:
        port = None
        deadline = time.time() + 60
        while port is None and time.time() < deadline:
            line = process.stdout.readline()
            if not line:
                break
            m = re.search(r"listening on http://127\.0\.0\.1:(\d+)", line)
            if m:
                port = int(m.group(1))
        log.flush()
        check(port is not None,
              "wavebenchd starts in the sandbox:\n" + open(log_path).read()[-3000:])
        status, body = get(port, "/api/status")
        check(status == 200, "GET /api/status")
        deadline = time.time() + 20
        while "bench thread:" not in open(log_path).read() and time.time() < deadline:
            time.sleep(0.2)
        started = open(log_path).read()
        scheduling = re.findall(r"bench thread: .*", started)
        if limits_as_unit:
            check(re.search(r"bench thread: SCHED_FIFO priority \d+, memory locked", started),
                  "SCHED_FIFO and locked memory from LimitRTPRIO/LimitMEMLOCK alone, no "
                  f"capability ({scheduling})")
        else:
            print(f"skipped: SCHED_FIFO under the unit's limits, which this machine cannot "
                  f"grant; the daemon said {scheduling}")
        cli = os.path.join(os.path.dirname(os.path.dirname(daemon)), "cli", "wavebench")
        run = subprocess.run([cli, "start", "static", "--daemon", f"http://127.0.0.1:{port}",
                              "--token-file", token, "--option", "positions=2",
                              "--option", "loads_nm=[0]", "--wait"],
                             capture_output=True, text=True, timeout=90)
        check(run.returncode == 0, f"a static run completes in the sandbox "
              f"({run.stdout.strip()[-500:]} {run.stderr.strip()[-500:]})")
        results = glob.glob(os.path.join(runs, "*", "results.json"))
        check(len(results) == 1 and json.load(open(results[0])).get("procedure") is not None,
              f"its results.json is written under the runs folder ({results})")
    finally:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(timeout=120)
        except subprocess.TimeoutExpired:
            process.kill()
            fail("wavebenchd did not stop on SIGTERM")
    log.flush()
    text = open(log_path).read()
    refused = [line for line in text.splitlines() if "Operation not permitted" in line and
               (limits_as_unit or "bench thread: SCHED_FIFO refused" not in line)]
    check(process.returncode == 0, f"wavebenchd stops cleanly on SIGTERM ({process.returncode})")
    check(not refused, f"nothing the daemon asked for was refused ({refused[:5]})")
    print("unit sandbox run: all checks passed")


if __name__ == "__main__":
    main()
