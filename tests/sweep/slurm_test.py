#!/usr/bin/env python3
"""`beltsim sweep --slurm --submit` against a real Slurm (Debian's slurm-wlm and munge): a
single-node cluster on this machine, started here by scripts/single_node_slurm.py (what the docs
give users) and stopped at the end whatever happens: munged with a key in a temporary folder,
slurmctld and slurmd in the foreground with a generated slurm.conf (proctrack/linuxproc,
task/none, this machine's CPU count). The sweep's job array and
its collecting job run there; the merged summary.csv must equal the same sweep run locally.
Waits are for events (the node idle, the jobs gone from the queue), never fixed sleeps.

usage: slurm_test.py BELTSIM  (as root: slurmd starts the jobs)
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BELTSIM = None
HERE = os.path.dirname(os.path.abspath(__file__))
GRID = os.path.join(HERE, "grid.lua")
# the cluster as a user starts one (docs/sweeps.md)
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
import single_node_slurm  # noqa: E402


class Slurm(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="beltsim_slurm_")
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.cluster = single_node_slurm.Cluster(self.dir)
        self.addCleanup(self.cluster.stop)  # runs even when the start fails half-way
        try:
            self.cluster.start()
        except RuntimeError as e:
            self.fail(str(e))
        self.env = self.cluster.env

    def query(self, args):
        return self.cluster.query(args)

    def wait(self, ready, what):
        try:
            self.cluster.wait(ready, what)
        except RuntimeError as e:
            self.fail(str(e))

    def logs(self):
        return self.cluster.logs()

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
        # the same command again, with nothing left: nothing submitted, the array's script kept
        with open(os.path.join(out, "sweep.sbatch")) as f:
            script = f.read()
        p = subprocess.run([BELTSIM, "sweep", GRID, "--slurm", "--submit", "--out", out], cwd=work,
                           capture_output=True, text=True, env=self.env, timeout=60)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("nothing to submit", p.stderr)
        with open(os.path.join(out, "sweep.sbatch")) as f:
            self.assertEqual(f.read(), script)


if __name__ == "__main__":
    BELTSIM = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
