#!/usr/bin/env python3
"""`beltsim sweep --slurm --submit` against a real Slurm (Debian's slurm-wlm and munge): a
single-node cluster on this machine, started here and stopped at the end whatever happens: munged
with a key in a temporary folder, slurmctld and slurmd in the foreground with a generated
slurm.conf (proctrack/linuxproc, task/none, this machine's CPU count). The sweep's job array and
its collecting job run there; the merged summary.csv must equal the same sweep run locally.
Waits are for events (the node idle, the jobs gone from the queue), never fixed sleeps.

usage: slurm_test.py BELTSIM  (as root: slurmd starts the jobs)
"""
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import unittest

BELTSIM = None
HERE = os.path.dirname(os.path.abspath(__file__))
GRID = os.path.join(HERE, "grid.lua")
LIMIT = 120.0  # [s] for the cluster to come up, and for the jobs to end


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Slurm(unittest.TestCase):
    def setUp(self):
        for program in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo"):
            if not shutil.which(program):
                self.fail(program + " is missing: apt-get install slurm-wlm munge (scripts/debian-packages-test.txt)")
        self.dir = tempfile.mkdtemp(prefix="beltsim_slurm_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.daemons = []
        self.addCleanup(self.stop_daemons)  # runs even when setUp fails half-way
        d = self.dir
        for sub in ("state", "spool", "munge"):
            os.mkdir(os.path.join(d, sub))
        os.chmod(os.path.join(d, "munge"), 0o700)
        key = os.path.join(d, "munge", "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        sock = os.path.join(d, "munge", "munge.sock")
        self.start(["munged", "--foreground", "--force", "--key-file=" + key, "--socket=" + sock,
                    "--pid-file=" + os.path.join(d, "munge", "munged.pid"),
                    "--log-file=" + os.path.join(d, "munge", "munged.log"),
                    "--seed-file=" + os.path.join(d, "munge", "munged.seed")])
        self.wait(lambda: os.path.exists(sock), "munged's socket")
        host = socket.gethostname()
        conf = os.path.join(d, "slurm.conf")
        with open(conf, "w") as f:
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
        self.env = dict(os.environ, SLURM_CONF=conf)
        self.start(["slurmctld", "-D", "-i", "-f", conf])
        self.start(["slurmd", "-D", "-f", conf])
        self.wait(lambda: self.query(["sinfo", "-h", "-o", "%T"]) == "idle", "the node idle")

    def start(self, args):
        log = open(os.path.join(self.dir, os.path.basename(args[0]) + ".out"), "w")
        self.daemons.append((subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT,
                                              env=getattr(self, "env", None)), log))

    def stop_daemons(self):
        for proc, log in reversed(self.daemons):
            if proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
            log.close()

    def query(self, args):
        p = subprocess.run(args, capture_output=True, text=True, env=self.env, timeout=30)
        return p.stdout.strip() if p.returncode == 0 else None

    def wait(self, ready, what):
        end = time.monotonic() + LIMIT
        while not ready():
            for proc, _ in self.daemons:
                self.assertIsNone(proc.poll(), "%s ended while waiting for %s; logs in %s: %s" % (
                    proc.args[0], what, self.dir, self.logs()))
            self.assertLess(time.monotonic(), end, "no %s after %g s: %s" % (what, LIMIT, self.logs()))
            time.sleep(0.1)

    def logs(self):
        text = ""
        for name in ("slurmctld.log", "slurmd.log", "munged.out", "slurmctld.out", "slurmd.out"):
            path = os.path.join(self.dir, name)
            if os.path.exists(path):
                with open(path) as f:
                    text += "\n--- %s\n%s" % (name, "".join(f.readlines()[-15:]))
        return text

    def test_the_job_array_gives_the_local_summary(self):
        # the folders' names hold what sh and sbatch's reader of #SBATCH lines treat specially, and
        # what Slurm expands in an --output path (%x, the job's name)
        out = os.path.join(self.dir, "cluster %x 'q' #1 $HOME")
        work = os.path.join(self.dir, "work \"d\" %j")
        os.mkdir(work)
        p = subprocess.run([BELTSIM, "sweep", GRID, "--slurm", "--submit", "--max-parallel", "2", "--time", "10",
                            "--out", out], cwd=work, capture_output=True, text=True, env=self.env, timeout=60)
        self.assertEqual(p.returncode, 0, p.stderr)
        array, collect = p.stdout.split()[-2:]
        with open(os.path.join(out, "sweep.sbatch")) as f:
            self.assertIn("#SBATCH --array=0-5%2\n", f.read())
        self.wait(lambda: self.query(["squeue", "-h", "-j", "%s,%s" % (array, collect)]) == "", "the jobs' end")
        summary = os.path.join(out, "summary.csv")
        self.assertTrue(os.path.exists(summary), "the collecting job wrote no summary: %s" % self.logs())
        # each job's output where the scripts name it, nothing anywhere else
        self.assertEqual(sorted(f for f in os.listdir(out) if f.startswith("slurm-")),
                         sorted(["slurm-%s-collect.out" % collect] + ["slurm-%s_%d.out" % (array, k) for k in range(6)]))
        self.assertEqual(os.listdir(work), [])
        p = subprocess.run([BELTSIM, "sweep", GRID, "--out", os.path.join(self.dir, "local")], cwd=self.dir,
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(summary) as a, open(os.path.join(self.dir, "local", "summary.csv")) as b:
            cluster, local = a.read(), b.read()
        self.assertEqual(cluster, local)
        self.assertEqual(cluster.count(",ok,"), 6)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
