"""Hostile output targets: devices, symlinks, directories, pipes, terminals, planted names.

The importer refuses every target that is not standard output, a regular file (or a new name in
an existing directory), a pipe or a terminal; it writes nothing unless every output can be
written; and its temporary files are never created through a symbolic link. Most tests drive
``truecost_gym.output`` directly (no Gymnasium needed); the command-line tests need Gymnasium.
"""

import io
import os
import random
import stat
import subprocess
import sys
import tempfile
import threading
import unittest
from unittest import mock

from truecost_gym import output
from truecost_gym.output import DIRECT, REPLACE, STDOUT, OutputRefused, check, check_all, write_all

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)

try:
    import gymnasium  # noqa: F401

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False


sys.path.insert(0, HERE)
from test_importer import InTemporaryDirectory, assert_one_line_error, run_cli  # noqa: E402


def snapshot(folder):
    """Every name in ``folder`` with its kind, link target and content (regular files)."""
    out = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        st = os.lstat(path)
        if stat.S_ISLNK(st.st_mode):
            out[name] = ("link", os.readlink(path))
        elif stat.S_ISREG(st.st_mode):
            with open(path, "rb") as f:
                out[name] = ("file", f.read(), stat.S_IMODE(st.st_mode))
        else:
            out[name] = ("other", stat.S_IFMT(st.st_mode), st.st_rdev)
    return out


def device_copy(folder):
    """A character device that is not a terminal, in ``folder``: a copy of /dev/full made with
    mknod where allowed (root), else a symbolic link to /dev/full."""
    path = os.path.join(folder, "full")
    rdev = os.stat("/dev/full").st_rdev
    try:
        os.mknod(path, 0o666 | stat.S_IFCHR, rdev)
    except (PermissionError, AttributeError, OSError):
        os.symlink("/dev/full", path)
    return path


def drain(fd, sink):
    """Reads ``fd`` to its end (or an error) into the bytearray ``sink``."""
    while True:
        try:
            chunk = os.read(fd, 65536)
        except OSError:
            return
        if not chunk:
            return
        sink.extend(chunk)


class Classification(InTemporaryDirectory):
    def refused(self, path, needle):
        with self.assertRaises(OutputRefused) as c:
            check(path)
        self.assertIn(needle, str(c.exception))
        self.assertNotIn("\n", str(c.exception))
        return str(c.exception)

    def test_kinds(self):
        self.assertEqual(check("-").kind, STDOUT)
        self.assertEqual(check(os.path.join(self.d, "new.json")).kind, REPLACE)
        existing = os.path.join(self.d, "old.json")
        open(existing, "w").close()
        self.assertEqual(check(existing).kind, REPLACE)
        fifo = os.path.join(self.d, "fifo")
        os.mkfifo(fifo)
        self.assertEqual(check(fifo).kind, DIRECT)

    def test_devices_directories_and_dangling_links_refused(self):
        self.refused(self.d, "it is a directory")
        self.refused("/dev/full", "it is a character device")
        self.refused("/dev/null", "it is a character device")
        copy = device_copy(self.d)
        self.refused(copy, "character device")
        dangling = os.path.join(self.d, "dangling")
        os.symlink(os.path.join(self.d, "nothing"), dangling)
        self.refused(dangling, "symbolic link to")
        self.refused(os.path.join(self.d, "no", "such", "x.json"), "no such directory")
        self.assertFalse(os.path.exists(os.path.join(self.d, "no")), "no directory created")
        blocker = os.path.join(self.d, "plain")
        open(blocker, "w").close()
        self.refused(os.path.join(blocker, "x.json"), "cannot write")

    def test_a_link_to_standard_output_follows_what_it_is(self):
        link = os.path.join(self.d, "so")
        os.symlink("/proc/self/fd/1", link)
        if not os.path.exists("/proc/self/fd/1"):
            self.skipTest("no /proc")
        code = ("import sys; from truecost_gym.output import check\n"
                "try:\n    print(check(sys.argv[1]).kind, file=sys.stderr)\n"
                "except Exception as e:\n    print('refused', e, file=sys.stderr)\n")
        env = dict(os.environ, PYTHONPATH=PYTHON_DIR)
        for where, expected in ((subprocess.PIPE, "direct"), (subprocess.DEVNULL, "refused"),
                                ("file", "replace")):
            with self.subTest(stdout=where):
                if where == "file":
                    with open(os.path.join(self.d, "redirected"), "w") as f:
                        done = subprocess.run([sys.executable, "-c", code, link], stdout=f,
                                              stderr=subprocess.PIPE, text=True, env=env)
                else:
                    done = subprocess.run([sys.executable, "-c", code, link], stdout=where,
                                          stderr=subprocess.PIPE, text=True, env=env)
                self.assertTrue(done.stderr.startswith(expected), done.stderr)

    def test_a_terminal_is_direct(self):
        master, slave = os.openpty()
        try:
            name = os.ttyname(slave)
            self.assertEqual(check(name).kind, DIRECT)
        finally:
            os.close(master)
            os.close(slave)

    def test_two_outputs_to_one_file_refused(self):
        a = os.path.join(self.d, "a.json")
        link = os.path.join(self.d, "alias.json")
        open(a, "w").close()
        os.symlink(a, link)
        for pair in ((a, a), (a, link), ("-", "-")):
            with self.subTest(pair=pair), self.assertRaises(OutputRefused) as c:
                check_all([("--out", pair[0]), ("--report", pair[1])])
            self.assertIn("--out and --report both name", str(c.exception))
        # The option is named in a refusal.
        with self.assertRaises(OutputRefused) as c:
            check_all([("--out", a), ("--report", self.d)])
        self.assertTrue(str(c.exception).startswith("--report: cannot write"), str(c.exception))

    def test_messages_escape_the_path(self):
        msg = self.refused(os.path.join(self.d, "x\x1b[2J\n", "y.json"), "no such directory")
        self.assertIn("x\\x1b[2J\\n", msg)
        self.assertNotIn("\x1b", msg)


class Writing(InTemporaryDirectory):
    def test_new_and_replaced_files_whole_with_the_old_mode(self):
        new = os.path.join(self.d, "new.json")
        old = os.path.join(self.d, "old.json")
        with open(old, "w") as f:
            f.write("old text that is longer than the new one")
        os.chmod(old, 0o640)
        write_all(list(zip(check_all([("--out", new), ("--report", old)]), ["é1\n", "2\n"])))
        self.assertEqual(snapshot(self.d)["old.json"], ("file", b"2\n", 0o640))
        umask = os.umask(0)
        os.umask(umask)
        self.assertEqual(snapshot(self.d)["new.json"], ("file", "é1\n".encode(), 0o666 & ~umask))
        self.assertEqual(sorted(os.listdir(self.d)), ["new.json", "old.json"])

    def test_a_link_to_a_file_replaces_the_file_and_keeps_the_link(self):
        real = os.path.join(self.d, "real.json")
        with open(real, "w") as f:
            f.write("old")
        os.chmod(real, 0o600)
        link = os.path.join(self.d, "link.json")
        os.symlink("real.json", link)
        write_all([(check(link), "new")])
        self.assertEqual(snapshot(self.d), {"link.json": ("link", "real.json"),
                                            "real.json": ("file", b"new", 0o600)})
        with open(link) as f:
            self.assertEqual(f.read(), "new")

    def test_a_fifo_is_written_directly_and_stays_a_fifo(self):
        fifo = os.path.join(self.d, "fifo")
        os.mkfifo(fifo)
        got = bytearray()

        def reader():
            fd = os.open(fifo, os.O_RDONLY)
            drain(fd, got)
            os.close(fd)

        t = threading.Thread(target=reader)
        t.start()
        write_all([(check(fifo), "x" * 200000)])
        t.join(10)
        self.assertEqual(bytes(got), b"x" * 200000)
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_a_terminal_is_written_directly(self):
        master, slave = os.openpty()
        got = bytearray()
        t = threading.Thread(target=drain, args=(master, got))
        t.start()
        try:
            write_all([(check(os.ttyname(slave)), "hello\n")])
        finally:
            os.close(slave)
            t.join(10)
            os.close(master)
        self.assertIn(b"hello", bytes(got))

    def test_nothing_is_written_when_one_target_fails_to_open(self):
        # --out is fine, --report was a FIFO when checked and a regular file when opened: the
        # report is refused and --out is not written either (its temporary file is removed).
        good = os.path.join(self.d, "good.json")
        with open(good, "w") as f:
            f.write("old")
        fifo = os.path.join(self.d, "report")
        os.mkfifo(fifo)
        targets = check_all([("--out", good), ("--report", fifo)])
        os.unlink(fifo)
        open(fifo, "w").close()
        before = snapshot(self.d)
        with self.assertRaises(OutputRefused) as c:
            write_all(list(zip(targets, ["new", "report"])))
        self.assertIn("changed since it was checked", str(c.exception))
        self.assertEqual(snapshot(self.d), before)
        self.assertEqual(before["good.json"][1], b"old")

    def test_a_target_that_became_a_device_is_not_replaced(self):
        path = os.path.join(self.d, "out.json")
        target = check(path)
        real_replace = os.replace

        def swap_then_replace(src, dst):
            raise AssertionError("os.replace must not be reached")

        device = device_copy(self.d)
        os.rename(device, path)
        with mock.patch.object(output.os, "replace", swap_then_replace):
            with self.assertRaises(OutputRefused) as c:
                write_all([(target, "text")])
        self.assertIn("it became a", str(c.exception))
        self.assertEqual(sorted(os.listdir(self.d)), ["out.json"], "the temporary file removed")
        self.assertFalse(stat.S_ISREG(os.lstat(path).st_mode))
        self.assertIs(os.replace, real_replace)

    def test_planted_symlinks_at_temporary_names_are_never_followed(self):
        # The temporary names come from tempfile's random sequence; plant a symlink at the first
        # name it will try (pointing at a victim file), and check that mkstemp's O_EXCL skips it.
        victim = os.path.join(self.d, "victim")
        with open(victim, "w") as f:
            f.write("victim")
        names = iter(["planted", "planted", "fresh123"])
        os.symlink(victim, os.path.join(self.d, ".truecost_gym.planted.tmp"))
        target = check(os.path.join(self.d, "out.json"))
        with mock.patch.object(tempfile, "_get_candidate_names", return_value=names):
            write_all([(target, "new")])
        snap = snapshot(self.d)
        self.assertEqual(snap["victim"][:2], ("file", b"victim"))
        self.assertEqual(snap[".truecost_gym.planted.tmp"], ("link", victim))
        self.assertEqual(snap["out.json"][:2], ("file", b"new"))
        self.assertEqual(len(snap), 3, snap)

    def test_temporary_names_are_not_predictable(self):
        made = []
        real = tempfile.mkstemp

        def spy(*a, **kw):
            fd, path = real(*a, **kw)
            made.append(os.path.basename(path))
            return fd, path

        with mock.patch.object(output.tempfile, "mkstemp", spy):
            for _ in range(5):
                write_all([(check(os.path.join(self.d, "out.json")), "x")])
        self.assertEqual(len(set(made)), 5, made)
        self.assertFalse(any(str(os.getpid()) in m for m in made), made)

    def test_standard_output(self):
        buf = io.BytesIO()
        fake = io.TextIOWrapper(buf, encoding="utf-8")
        with mock.patch.object(sys, "stdout", fake):
            write_all([(check("-"), "é\n")])
        self.assertEqual(buf.getvalue(), "é\n".encode())


class FuzzedTargets(unittest.TestCase):
    """The fuzz class "importer output targets": random pairs of targets of every kind, each
    written or refused as a whole, with the directory checked after every run."""

    KINDS = ("new", "existing", "dir", "missing_dir", "device", "link_to_device", "dangling",
             "link_to_file", "fifo", "same_as_other", "stdout", "under_a_file")

    def make(self, d, kind, i, other):
        path = os.path.join(d, f"t{i}")
        if kind == "new":
            return path, "written"
        if kind == "existing":
            with open(path, "w") as f:
                f.write("old")
            return path, "written"
        if kind == "dir":
            os.mkdir(path)
            return path, "refused"
        if kind == "missing_dir":
            return os.path.join(d, f"missing{i}", "x.json"), "refused"
        if kind == "device":
            dev = device_copy(d)
            os.rename(dev, path)
            return path, "refused"
        if kind == "link_to_device":
            os.symlink("/dev/full", path)
            return path, "refused"
        if kind == "dangling":
            os.symlink(os.path.join(d, "nowhere"), path)
            return path, "refused"
        if kind == "link_to_file":
            with open(path + ".real", "w") as f:
                f.write("old")
            os.symlink(path + ".real", path)
            return path, "written"
        if kind == "fifo":
            os.mkfifo(path)
            return path, "pipe"
        if kind == "same_as_other":
            return (other, "refused") if other is not None else (path, "written")
        if kind == "stdout":
            return "-", "stdout"
        if kind == "under_a_file":
            with open(path, "w") as f:
                f.write("a file")
            return os.path.join(path, "x.json"), "refused"
        raise AssertionError(kind)

    def test_random_pairs(self):
        # A campaign sets its own seed and count (docs/guide/problem-files.md, "Fuzzing").
        rng = random.Random(int(os.environ.get("TRUECOST_FUZZ_SEED", "20261207")))
        extra = int(os.environ.get("TRUECOST_FUZZ_CASES", "100"))
        cases = [(a, b) for a in self.KINDS for b in self.KINDS]
        rng.shuffle(cases)
        cases += [(rng.choice(self.KINDS), rng.choice(self.KINDS)) for _ in range(extra)]
        for kinds in cases:
            if kinds[0] == "same_as_other":
                kinds = ("new", kinds[1])
            with self.subTest(kinds=kinds), tempfile.TemporaryDirectory() as d:
                self.one_run(d, kinds, rng)

    def one_run(self, d, kinds, rng):
        paths, fates = [], []
        for i, kind in enumerate(kinds):
            p, fate = self.make(d, kind, i, paths[0] if paths else None)
            if fate == "stdout" and "stdout" in fates:
                fate = "refused"  # both on standard output
            paths.append(p)
            fates.append(fate)
        texts = [f"text {i} {rng.random()}\n" for i in range(len(paths))]
        before = snapshot(d)
        readers, got = [], {}
        for p, fate in zip(paths, fates):
            if fate == "pipe":
                got[p] = bytearray()

                def reader(p=p):
                    fd = os.open(p, os.O_RDONLY)  # waits for a writer
                    drain(fd, got[p])
                    os.close(fd)

                t = threading.Thread(target=reader, daemon=True)
                t.start()
                readers.append(t)
        buf = io.BytesIO()
        fake = io.TextIOWrapper(buf, encoding="utf-8")
        try:
            with mock.patch.object(sys, "stdout", fake):
                write_all(list(zip(check_all(list(zip(("--out", "--report"), paths))),
                                   texts)))
            refused = None
        except OutputRefused as e:
            refused = str(e)
        finally:
            for p, t in zip(got, readers):
                t.join(0.05)
                for _ in range(200):  # release a reader whose writer never came
                    if not t.is_alive():
                        break
                    try:
                        os.close(os.open(p, os.O_WRONLY | os.O_NONBLOCK))
                    except OSError:
                        pass
                    t.join(0.05)
                self.assertFalse(t.is_alive())
        after = snapshot(d)
        if "refused" in fates:
            self.assertIsNotNone(refused, (kinds, paths))
            self.assertNotIn("\n", refused)
            self.assertEqual(after, before, "nothing written, no temporary file left")
            self.assertEqual(buf.getvalue(), b"")
            for p in got:
                self.assertEqual(bytes(got[p]), b"")
            return
        self.assertIsNone(refused, (kinds, refused))
        for p, fate, text in zip(paths, fates, texts):
            if fate == "written":
                with open(p, "rb") as f:
                    self.assertEqual(f.read(), text.encode())
            elif fate == "pipe":
                self.assertEqual(bytes(got[p]), text.encode())
                self.assertTrue(stat.S_ISFIFO(os.lstat(p).st_mode))
            elif fate == "stdout":
                self.assertEqual(buf.getvalue(), text.encode())
        # Links stay links, and no name appeared but the new targets.
        for name, entry in before.items():
            if entry[0] == "link":
                self.assertEqual(after[name], entry)
            if entry[0] == "other":
                self.assertEqual(after[name], entry)
        extra = set(after) - set(before)
        self.assertEqual(extra, {os.path.basename(p) for p, fate, k in zip(paths, fates, kinds)
                                 if k == "new"})


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class CommandLine(InTemporaryDirectory):
    def one_line_error(self, out, status=2):
        return assert_one_line_error(self, out, status)

    def test_directories_and_devices_refused_in_one_line_nothing_written(self):
        out_json = os.path.join(self.d, "out.json")
        device = device_copy(self.d)
        before_dev = os.lstat(device)
        for args in (["--out", self.d], ["--out", out_json, "--report", self.d],
                     ["--out", device], ["--out", out_json, "--report", device],
                     ["--out", out_json, "--report", os.path.join(self.d, "none", "r.json")]):
            with self.subTest(args=args):
                done = run_cli("export", "FrozenLake-v1", "--quiet", *args)
                self.one_line_error(done)
                self.assertFalse(os.path.exists(out_json), "--out written before --report")
        after_dev = os.lstat(device)
        self.assertEqual((before_dev.st_mode, before_dev.st_ino, before_dev.st_rdev),
                         (after_dev.st_mode, after_dev.st_ino, after_dev.st_rdev))
        self.assertFalse(os.path.exists(os.path.join(self.d, "none")))

    def test_a_link_to_standard_output(self):
        link = os.path.join(self.d, "so")
        os.symlink("/proc/self/fd/1", link)
        # A pipe: written directly; the summary goes to stderr, not into the data.
        done = run_cli("export", "FrozenLake-v1", "--quiet", "--out", link)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertTrue(done.stdout.startswith('{\n  "format": "truecost-stochastic/1"'))
        self.assertTrue(done.stdout.endswith("]\n}\n"), done.stdout[-40:])
        self.assertIn("wrote", done.stderr)
        # /dev/null is a device: refused, and the link is left alone.
        done = run_cli("export", "FrozenLake-v1", "--quiet", "--out", link,
                       stdout=subprocess.DEVNULL)
        self.one_line_error(done)
        self.assertEqual(os.readlink(link), "/proc/self/fd/1")

    def test_escapes_in_the_out_path_never_reach_the_terminal(self):
        name = os.path.join(self.d, "a\x1b]0;owned\x07b.json")
        done = run_cli("export", "FrozenLake-v1", "--quiet", "--out", name)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("a\\x1b]0;owned\\x07b.json", done.stdout)
        self.assertNotIn("\x1b", done.stdout)
        bad = os.path.join(self.d, "x\x1b[2J", "y.json")
        self.one_line_error(run_cli("export", "FrozenLake-v1", "--out", bad))


if __name__ == "__main__":
    unittest.main()
