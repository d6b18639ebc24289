#!/usr/bin/python3
"""The maintainer scripts' life cycle in a throw-away root (issue #22, item 13): postinst
configure makes the user, the group and the settings; `remove` keeps everything; `purge` removes
the settings, the logs, the token, the enablement link, the user and the group, and keeps the
runs unless WAVEBENCH_PURGE_RUNS=yes. The scripts run under sh with $DPKG_ROOT set to the fake
root and stubs of adduser, deluser, delgroup, getent and systemctl first on PATH, which keep their
users in the fake root's etc/passwd and etc/group: nothing on this machine is touched.

Usage: maintainer_scripts_test.py SOURCE_DIR WORK_DIR
"""
import os
import shutil
import subprocess
import sys

from checks import check

STUB = r"""#!/usr/bin/python3
# Stub of {name} for maintainer_scripts_test.py: users and groups in $DPKG_ROOT/etc.
import os, sys
root = os.environ["DPKG_ROOT"]
name, args = {name!r}, [a for a in sys.argv[1:] if not a.startswith("--")]
with open(os.path.join(root, "calls.log"), "a") as log:
    log.write(" ".join([name] + sys.argv[1:]) + "\n")
def table(kind):
    path = os.path.join(root, "etc", kind)
    return path, [l.split(":") for l in open(path).read().splitlines() if l]
def save(path, rows):
    open(path, "w").write("".join(":".join(r) + "\n" for r in rows))
if name == "getent":
    path, rows = table(sys.argv[1])
    hit = [r for r in rows if r[0] == sys.argv[2]]
    print(*(":".join(r) for r in hit))
    sys.exit(0 if hit else 2)
if name == "adduser" and "--system" in sys.argv:
    user = args[-1]
    pw, users = table("passwd"); gr, groups = table("group")
    groups.append([user, "x", "990", ""]); users.append([user, "x", "990", "990", "", "/", ""])
    save(pw, users); save(gr, groups)
elif name == "adduser":  # adduser USER GROUP
    gr, groups = table("group")
    for g in groups:
        if g[0] == args[1]:
            g[3] = ",".join([m for m in g[3].split(",") if m] + [args[0]])
    save(gr, groups)
elif name == "deluser":
    pw, users = table("passwd"); gr, groups = table("group")
    save(pw, [u for u in users if u[0] != args[0]])
    for g in groups:
        g[3] = ",".join(m for m in g[3].split(",") if m and m != args[0])
    save(gr, groups)
elif name == "delgroup":
    gr, groups = table("group")
    save(gr, [g for g in groups if g[0] != args[0]])
"""


def make_root(path, source_dir):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(os.path.join(path, "etc"))
    open(os.path.join(path, "etc/passwd"), "w").write("root:x:0:0:root:/root:/bin/sh\n")
    open(os.path.join(path, "etc/group"), "w").write("root:x:0:\ndialout:x:20:\n")
    os.makedirs(os.path.join(path, "usr/share/wavebench"))
    shutil.copy(os.path.join(source_dir, "configs/daemon/wavebenchd.env"),
                os.path.join(path, "usr/share/wavebench/wavebenchd.env"))


def run(script_dir, stubs, root, script, *args, env_extra=None):
    env = {"PATH": stubs + ":/usr/sbin:/usr/bin:/sbin:/bin", "DPKG_ROOT": root}
    env.update(env_extra or {})
    result = subprocess.run(["sh", "-e", os.path.join(script_dir, script), *args], env=env,
                            capture_output=True, text=True)
    check(result.returncode == 0, f"{script} {' '.join(args)} exits 0 ({result.stderr.strip()})")
    return result


def daemon_made_state(root):
    """What the daemon's first start makes: StateDirectory, LogsDirectory, token, a run."""
    for path in ["var/lib/wavebench/runs/20260101-000000-sim/samples.wbs",
                 "var/lib/wavebench/runs/index.sqlite", "var/lib/wavebench/daemon.token",
                 "var/log/wavebench/wavebenchd.log"]:
        os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
        open(os.path.join(root, path), "w").write("x")
    links = os.path.join(root, "etc/systemd/system/multi-user.target.wants")
    os.makedirs(links)
    os.symlink("/usr/lib/systemd/system/wavebenchd.service",
               os.path.join(links, "wavebenchd.service"))


def exists(root, path):
    return os.path.lexists(os.path.join(root, path))


def user_lines(root):
    return (open(os.path.join(root, "etc/passwd")).read(),
            open(os.path.join(root, "etc/group")).read())


def main():
    source_dir, work = sys.argv[1], sys.argv[2]
    scripts = os.path.join(source_dir, "packaging", "debian")
    shutil.rmtree(work, ignore_errors=True)
    stubs = os.path.join(work, "stubs")
    os.makedirs(stubs)
    for name in ["adduser", "deluser", "delgroup", "getent", "systemctl"]:
        path = os.path.join(stubs, name)
        open(path, "w").write(STUB.replace("{name!r}", repr(name)))
        os.chmod(path, 0o755)
    for script in ["postinst", "prerm", "postrm"]:
        subprocess.run(["sh", "-n", os.path.join(scripts, script)], check=True)
    print("ok: the maintainer scripts parse (sh -n)")

    for purge_runs in [False, True]:
        root = os.path.join(work, "root-purge-runs" if purge_runs else "root")
        make_root(root, source_dir)
        run(scripts, stubs, root, "postinst", "configure")
        passwd, group = user_lines(root)
        check(passwd.count("\nwavebench:") == 1 and "\nwavebench:" in group and
              "dialout:x:20:wavebench" in group,
              "postinst configure makes the user and group wavebench (in dialout)")
        check(exists(root, "etc/wavebench/wavebenchd.env"), "postinst makes the settings")
        run(scripts, stubs, root, "postinst", "configure", "0.1.0")
        check(user_lines(root)[0].count("\nwavebench:") == 1, "a second configure adds no user")
        daemon_made_state(root)

        run(scripts, stubs, root, "prerm", "remove")
        run(scripts, stubs, root, "postrm", "remove")
        check(all(exists(root, p) for p in ["etc/wavebench/wavebenchd.env",
                                            "var/log/wavebench", "var/lib/wavebench/daemon.token",
                                            "var/lib/wavebench/runs/index.sqlite"]) and
              "\nwavebench:" in user_lines(root)[0],
              "remove keeps settings, logs, state, runs, user")

        extra = {"WAVEBENCH_PURGE_RUNS": "yes"} if purge_runs else None
        result = run(scripts, stubs, root, "postrm", "purge", env_extra=extra)
        passwd, group = user_lines(root)
        check("wavebench" not in passwd and "wavebench" not in group,
              "purge deletes the user and the group (and the dialout membership)")
        for path in ["etc/wavebench", "var/log/wavebench", "var/lib/wavebench/daemon.token",
                     "etc/systemd/system/multi-user.target.wants/wavebenchd.service"]:
            check(not exists(root, path), f"purge removes /{path}")
        if purge_runs:
            check(not exists(root, "var/lib/wavebench"),
                  "purge with WAVEBENCH_PURGE_RUNS=yes removes /var/lib/wavebench and the runs")
        else:
            check(exists(root, "var/lib/wavebench/runs/20260101-000000-sim/samples.wbs") and
                  exists(root, "var/lib/wavebench/runs/index.sqlite") and
                  "/var/lib/wavebench/runs" in result.stderr,
                  "purge keeps the runs (the user's measurements) and says where they are")
        calls = open(os.path.join(root, "calls.log")).read()
        check("systemctl" not in calls, "nothing talks to the host's systemd under $DPKG_ROOT")
        run(scripts, stubs, root, "postrm", "purge", env_extra=extra)
        print("ok: a second purge finds nothing to do")
    print("maintainer scripts: all checks passed")


if __name__ == "__main__":
    main()
