#!/usr/bin/python3
"""The built wavebenchd runs under the packaged unit's sandbox (issue #22, item 13), as far as it
can be rebuilt without systemd as PID 1, from the unit's own settings: bubblewrap gives the
mounts (ProtectSystem=strict: all read-only but StateDirectory= and LogsDirectory=; PrivateTmp=;
ProtectHome=), the kernel the rest: SystemCallFilter= (expanded by systemd-analyze
syscall-filter) with SystemCallErrorNumber= and RestrictAddressFamilies= as a seccomp program,
MemoryDenyWriteExecute= as PR_SET_MDWE, NoNewPrivileges=, no capabilities, LimitRTPRIO=,
LimitMEMLOCK= and UMask=, as the unprivileged user nobody. The unit's ExecStart= runs, with its
environment as an operator's wavebenchd.env would set it.
A probe shows the sandbox bites (a packet socket, W+X memory and writes outside the state folder
refused); then the daemon, on the simulated bench with the real clock, gets SCHED_FIFO and
locked memory from the limits alone (where this machine can grant them), serves /api/status,
records a static run with its results and stops cleanly on SIGTERM.

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
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import time

import seccomp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import packaged_unit  # noqa: E402

from checks import check, fail

PR_CAPBSET_DROP = 24
PR_SET_MDWE = 65
PR_MDWE_REFUSE_EXEC_GAIN = 1


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


def seccomp_program(unit, path):
    """SystemCallFilter=, SystemCallErrorNumber= and RestrictAddressFamilies= as one seccomp
    program (BPF) in path, for bwrap --seccomp."""
    allowed = allowed_syscalls(unit)
    families = [getattr(socket, f)
                for f in packaged_unit.values(unit, "RestrictAddressFamilies")[-1].split()]
    error = getattr(errno, packaged_unit.values(unit, "SystemCallErrorNumber")[-1])
    f = seccomp.SyscallFilter(defaction=seccomp.ERRNO(error))
    for name in allowed - {"socket"}:
        try:
            f.add_rule(seccomp.ALLOW, name)
        except (RuntimeError, ValueError):
            pass  # a name this kernel or architecture does not have
    for family in families:
        f.add_rule(seccomp.ALLOW, "socket", seccomp.Arg(0, seccomp.EQ, family))
    with open(path, "wb") as out:
        f.export_bpf(out)
    print(f"sandbox: {len(allowed)} system calls allowed, socket families {families}, "
          f"others refused with {errno.errorcode[error]}")


def grantable(limit, wanted):
    """The unit's limit, or this machine's hard limit where it is lower and cannot be raised
    (a container without CAP_SYS_RESOURCE)."""
    soft, hard = resource.getrlimit(limit)
    try:
        resource.setrlimit(limit, (soft, wanted))
        return wanted
    except (ValueError, OSError):
        return hard


def process_settings(unit, user):
    """The preexec function that applies the unit's limits, umask, capabilities, user and
    MemoryDenyWriteExecute=, and whether the limits are the unit's."""
    check(packaged_unit.values(unit, "CapabilityBoundingSet") == [""] and
          packaged_unit.values(unit, "AmbientCapabilities") == [""], "no capability kept")
    check(packaged_unit.values(unit, "NoNewPrivileges") == ["yes"] and
          packaged_unit.values(unit, "MemoryDenyWriteExecute") == ["yes"],
          "NoNewPrivileges and MemoryDenyWriteExecute")
    unit_rtprio = int(packaged_unit.values(unit, "LimitRTPRIO")[-1])
    unit_memlock = packaged_unit.values(unit, "LimitMEMLOCK")[-1]
    unit_memlock = resource.RLIM_INFINITY if unit_memlock == "infinity" else int(unit_memlock)
    umask = int(packaged_unit.values(unit, "UMask")[-1], 8)
    rtprio = grantable(resource.RLIMIT_RTPRIO, unit_rtprio)
    memlock = grantable(resource.RLIMIT_MEMLOCK, unit_memlock)
    limits_as_unit = (rtprio, memlock) == (unit_rtprio, unit_memlock)
    print(f"limits: RTPRIO {rtprio}, MEMLOCK {memlock}" +
          ("" if limits_as_unit else " (this machine cannot grant the unit's limits)"))
    libc = ctypes.CDLL(None, use_errno=True)

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

    return enter, limits_as_unit


def mounts(unit, state, logs):
    """bwrap's view of the file system for the unit's ProtectSystem=, PrivateTmp=,
    ProtectHome=, StateDirectory= and LogsDirectory= (PrivateDevices=no: the host's /dev)."""
    v = lambda key: packaged_unit.values(unit, key)  # noqa: E731
    check(v("ProtectSystem") == ["strict"] and v("PrivateTmp") == ["yes"] and
          v("ProtectHome") == ["yes"] and v("StateDirectory") == ["wavebench"] and
          v("LogsDirectory") == ["wavebench"] and v("PrivateDevices") == ["no"],
          "the unit's file system settings are the ones rebuilt here")
    args = ["--unshare-user", "--ro-bind", "/", "/", "--dev-bind", "/dev", "/dev",
            "--bind", "/proc", "/proc", "--tmpfs", "/tmp", "--tmpfs", "/var/tmp",
            "--tmpfs", "/home", "--tmpfs", "/root"]
    for parent, folder in [("/var/lib", state), ("/var/log", logs)]:
        args += ["--tmpfs", parent, "--dir", parent + "/wavebench",
                 "--bind", folder, parent + "/wavebench", "--remount-ro", parent]
    return args


def exec_start(unit, environment):
    """ExecStart= as systemd expands it: ${VAR} within a word, $VAR split into words."""
    words = []
    for word in shlex.split(packaged_unit.values(unit, "ExecStart")[-1]):
        m = re.fullmatch(r"\$(\w+)", word)
        if m:
            words += environment.get(m.group(1), "").split()
        else:
            words.append(re.sub(r"\$\{(\w+)\}", lambda n: environment.get(n.group(1), ""), word))
    return words


def unit_environment(unit, overrides):
    environment = dict(v.split("=", 1) for v in packaged_unit.values(unit, "Environment"))
    environment.update(overrides)
    return environment


def descendant(pid, name):
    """The pid of a process called name below pid (bwrap runs the daemon as its child)."""
    children = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                stat = open(f"/proc/{entry}/stat").read()
            except OSError:
                continue
            comm = stat[stat.index("(") + 1:stat.rindex(")")]
            ppid = int(stat[stat.rindex(")") + 2:].split()[1])
            children.setdefault(ppid, []).append((int(entry), comm))
    todo = [pid]
    while todo:
        for child, comm in children.get(todo.pop(), []):
            if comm == name:
                return child
            todo.append(child)
    return None


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
for path in ["/usr/share/wavebench-probe", "/var/lib/wavebench-probe", "/etc/wavebench-probe"]:
    try:
        open(path, "w")
    except OSError:
        refused.append("write:" + path)
open("/var/lib/wavebench/probe", "w").close()
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
    check(shutil.which("bwrap") is not None, "bwrap is installed (Debian package bubblewrap)")
    # The unit as the package writes it, with a prefix whose bin/ holds the built daemon.
    prefix = os.path.join(work, "prefix")
    os.makedirs(os.path.join(prefix, "bin"))
    os.symlink(daemon, os.path.join(prefix, "bin", "wavebenchd"))
    unit = packaged_unit.write_unit(source_dir, prefix, os.path.join(work, "unit"))
    user = pwd.getpwnam("nobody")
    state, logs = os.path.join(work, "state"), os.path.join(work, "logs")
    for folder in [work, state, logs]:
        os.makedirs(folder, exist_ok=True)
        if os.getuid() == 0:
            os.chown(folder, user.pw_uid, user.pw_gid)
    program = os.path.join(work, "seccomp.bpf")
    seccomp_program(unit, program)
    enter, limits_as_unit = process_settings(unit, user)
    bwrap = ["bwrap"] + mounts(unit, state, logs)

    def sandboxed(command, **kwargs):
        with open(program, "rb") as bpf:
            fd = bpf.fileno()
            return subprocess.Popen(bwrap + ["--seccomp", str(fd)] + command, preexec_fn=enter,
                                    pass_fds=(fd,), **kwargs)

    probe = sandboxed(["/usr/bin/python3", "-c", PROBE], stdout=subprocess.PIPE,
                      stderr=subprocess.PIPE, text=True)
    out, err = probe.communicate(timeout=60)
    words = out.split()
    check(probe.returncode == 0 and words[:2] == ["AF_PACKET", "W+X"] and
          all(("write:" + p) in words for p in ["/usr/share/wavebench-probe",
                                                "/var/lib/wavebench-probe",
                                                "/etc/wavebench-probe"]) and
          words[-1] in ("CAN:open", "CAN:EAFNOSUPPORT") and
          os.path.exists(os.path.join(state, "probe")),
          "in the sandbox a packet socket, W+X memory and writes outside /var/lib/wavebench"
          f" are refused, a CAN socket is not ({out.strip()!r} {err.strip()[-300:]})")
    os.remove(os.path.join(state, "probe"))

    # What an operator's /etc/wavebench/wavebenchd.env would say: the bench and the address.
    config = real_clock_sim_config(source_dir, work)
    command = exec_start(unit, unit_environment(unit, {"WAVEBENCH_BENCH_CONFIG": config,
                                                       "WAVEBENCH_LISTEN": "127.0.0.1:0"}))
    print("ExecStart: " + " ".join(command))
    log_path = os.path.join(work, "wavebenchd.err")
    log = open(log_path, "w+")
    process = sandboxed(command, stdout=subprocess.PIPE, stderr=log, text=True, cwd="/")
    runs, token = os.path.join(state, "runs"), os.path.join(state, "daemon.token")
    daemon_pid = None
    try:
        port = packaged_unit.listening_port(process.stdout)
        log.flush()
        check(port is not None,
              "wavebenchd starts in the sandbox:\n" + open(log_path).read()[-3000:])
        daemon_pid = descendant(process.pid, "wavebenchd")
        check(daemon_pid is not None and os.stat(f"/proc/{daemon_pid}").st_uid == user.pw_uid,
              f"the daemon runs as {user.pw_name} (pid {daemon_pid})")
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
              f"its results.json is written under /var/lib/wavebench/runs ({results})")
        check(os.stat(results[0]).st_mode & 0o777 == 0o640, "written with the unit's UMask")
    finally:
        os.kill(daemon_pid or process.pid, signal.SIGTERM)
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
    check(glob.glob(os.path.join(logs, "*")) != [], "its log is written under /var/log/wavebench")
    print("unit sandbox run: all checks passed")


if __name__ == "__main__":
    main()
