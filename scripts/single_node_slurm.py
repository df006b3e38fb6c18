#!/usr/bin/env python3
"""A Slurm cluster of one node on this machine, to try `beltsim sweep --slurm` without a cluster
(docs/sweeps.md, "Trying it on one machine"); the Slurm test (tests/sweep/slurm_test.py) starts
its cluster with this too.

Debian's slurm-wlm and munge (apt-get install slurm-wlm munge); as root, since slurmd starts the
jobs as their users. Everything lives in one folder: munge's key and socket, slurm.conf, the
daemons' state, spool, logs and process ids. Nothing of the system's own Slurm or munge set-up
(/etc/slurm, /etc/munge, their services) is read or changed.

    sudo python3 scripts/single_node_slurm.py start DIR   # prints: export SLURM_CONF=DIR/slurm.conf
    export SLURM_CONF=DIR/slurm.conf
    beltsim sweep FILE --slurm --submit                   # then squeue, sacct-less: see DIR/*.log
    sudo python3 scripts/single_node_slurm.py stop DIR

The daemons: munged (its own key and socket), slurmctld and slurmd in the foreground of processes
of their own (proctrack/linuxproc, task/none: no cgroups needed), one partition `test` with this
machine's CPUs, ports chosen free.
"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

LIMIT = 120.0  # [s] for the cluster to come up (slurmctld's start on a slow machine)
PROGRAMS = ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo")
PIDS = "daemons.pid"  # one process id a line, in the order started


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Cluster:
    """a single-node Slurm in folder d; start() brings it up (raising RuntimeError with the
    daemons' logs when it does not come up), stop() ends it; env is the environment for sbatch"""

    def __init__(self, d):
        self.dir = os.path.abspath(d)
        self.conf = os.path.join(self.dir, "slurm.conf")
        self.env = dict(os.environ, SLURM_CONF=self.conf)
        self.daemons = []

    def start(self, detach=False):
        """detach: the daemons in sessions of their own, outliving this process (the command line)"""
        missing = [p for p in PROGRAMS if not shutil.which(p)]
        if missing:
            raise RuntimeError(" ".join(missing) + " missing: apt-get install slurm-wlm munge")
        d = self.dir
        for sub in ("state", "spool", "munge"):
            os.makedirs(os.path.join(d, sub), exist_ok=True)
        os.chmod(os.path.join(d, "munge"), 0o700)
        key = os.path.join(d, "munge", "munge.key")
        if not os.path.exists(key):
            with open(key, "wb") as f:
                f.write(os.urandom(1024))
            os.chmod(key, 0o400)
        sock = os.path.join(d, "munge", "munge.sock")
        self._start(["munged", "--foreground", "--force", "--key-file=" + key, "--socket=" + sock,
                     "--pid-file=" + os.path.join(d, "munge", "munged.pid"),
                     "--log-file=" + os.path.join(d, "munge", "munged.log"),
                     "--seed-file=" + os.path.join(d, "munge", "munged.seed")], detach)
        self.wait(lambda: os.path.exists(sock), "munged's socket")
        host = socket.gethostname()
        with open(self.conf, "w") as f:
            f.write("\n".join([
                "ClusterName=beltsimtest", "SlurmctldHost=%s(127.0.0.1)" % host,
                "SlurmUser=root", "SlurmdUser=root",
                "SlurmctldPort=%d" % free_port(), "SlurmdPort=%d" % free_port(),
                "AuthType=auth/munge", "CredType=cred/munge", "AuthInfo=socket=" + sock,
                "StateSaveLocation=" + os.path.join(d, "state"), "SlurmdSpoolDir=" + os.path.join(d, "spool"),
                "SlurmctldPidFile=" + os.path.join(d, "slurmctld.pid"),
                "SlurmdPidFile=" + os.path.join(d, "slurmd.pid"),
                "SlurmctldLogFile=" + os.path.join(d, "slurmctld.log"),
                "SlurmdLogFile=" + os.path.join(d, "slurmd.log"),
                "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none",
                "SchedulerType=sched/backfill", "SelectType=select/cons_tres", "SelectTypeParameters=CR_CPU",
                "ReturnToService=2", "MpiDefault=none", "JobAcctGatherType=jobacct_gather/none",
                "AccountingStorageType=accounting_storage/none",
                "NodeName=%s NodeAddr=127.0.0.1 CPUs=%d State=UNKNOWN" % (host, os.cpu_count()),
                "PartitionName=test Nodes=%s Default=YES MaxTime=INFINITE State=UP" % host, ""]))
        self._start(["slurmctld", "-D", "-i", "-f", self.conf], detach)
        self._start(["slurmd", "-D", "-f", self.conf], detach)
        self.wait(lambda: self.query(["sinfo", "-h", "-o", "%T"]) == "idle", "the node idle")

    def _start(self, args, detach):
        log = open(os.path.join(self.dir, os.path.basename(args[0]) + ".out"), "w")
        proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                env=self.env, start_new_session=detach)
        self.daemons.append((proc, log))
        with open(os.path.join(self.dir, PIDS), "a") as f:
            f.write("%d\n" % proc.pid)

    def stop(self):
        """ends the daemons this object started, or (from the command line) those DIR records"""
        if self.daemons:
            for proc, log in reversed(self.daemons):
                if proc.poll() is None:
                    proc.terminate()
                    try:
                        proc.wait(timeout=10)
                    except subprocess.TimeoutExpired:
                        proc.kill()
                        proc.wait()
                log.close()
        else:
            path = os.path.join(self.dir, PIDS)
            if not os.path.exists(path):
                return
            with open(path) as f:
                pids = [int(x) for x in f.read().split()]
            for pid in reversed(pids):
                try:
                    os.kill(pid, signal.SIGTERM)
                except ProcessLookupError:
                    continue
                end = time.monotonic() + 10
                while os.path.exists("/proc/%d" % pid) and time.monotonic() < end:
                    time.sleep(0.05)
        pids = os.path.join(self.dir, PIDS)
        if os.path.exists(pids):
            os.remove(pids)

    def query(self, args):
        p = subprocess.run(args, capture_output=True, text=True, env=self.env, timeout=30)
        return p.stdout.strip() if p.returncode == 0 else None

    def wait(self, ready, what):
        end = time.monotonic() + LIMIT
        while not ready():
            for proc, _ in self.daemons:
                if proc.poll() is not None:
                    raise RuntimeError("%s ended while waiting for %s; logs in %s:%s" % (
                        proc.args[0], what, self.dir, self.logs()))
            if time.monotonic() > end:
                raise RuntimeError("no %s after %g s:%s" % (what, LIMIT, self.logs()))
            time.sleep(0.1)

    def logs(self):
        text = ""
        for name in ("slurmctld.log", "slurmd.log", "munged.out", "slurmctld.out", "slurmd.out"):
            path = os.path.join(self.dir, name)
            if os.path.exists(path):
                with open(path) as f:
                    text += "\n--- %s\n%s" % (name, "".join(f.readlines()[-15:]))
        return text


def main(argv):
    if len(argv) != 3 or argv[1] not in ("start", "stop"):
        sys.stderr.write("usage: %s start|stop DIR\n" % argv[0])
        return 2
    c = Cluster(argv[2])
    if argv[1] == "stop":
        c.stop()
        return 0
    os.makedirs(c.dir, exist_ok=True)
    try:
        c.start(detach=True)
    except RuntimeError as e:
        c.stop()
        sys.stderr.write("single_node_slurm: %s\n" % e)
        return 1
    print("export SLURM_CONF=%s" % c.conf)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
