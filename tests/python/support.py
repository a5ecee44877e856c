"""What the Python suites share: where the sources and the peensim binary are, temporary
directories, and running the command line for the byte-for-byte comparisons."""

import os
import shutil
import subprocess
import tempfile
import unittest

SOURCE_DIR = os.environ["PEENSIM_SOURCE_DIR"]
BINARY = os.environ["PEENSIM_BINARY"]


def scene(name):
    return os.path.join(SOURCE_DIR, "scenes", name)


def cli(*args, check=True):
    """Runs the peensim command line; returns (exit code, stdout + stderr)."""
    done = subprocess.run([BINARY, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"peensim {' '.join(args)} exited {done.returncode}:\n{done.stdout}")
    return done.returncode, done.stdout


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


class TempDirTest(unittest.TestCase):
    """A test case with a fresh directory, self.tmp, removed afterwards."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="peensim-py-")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def path(self, *parts):
        return os.path.join(self.tmp, *parts)
