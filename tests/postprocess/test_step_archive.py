"""step_archive's parked copies (docs/sweeps.md "Parking a stopped point"): park writes every file
xz-compressed with parked.json last, replaces an older copy only when complete, survives the step
removing a file once it is linked, and unpark gives the bytes and modification times back, only
into a step without done.json and only while the archive has no done.json either; drop_parked
removes it; restore/keep leave the parked folder alone."""

import json
import lzma
import os
import tempfile
import unittest
from pathlib import Path

from wheelsim_post import step_archive


def write(path, data, mtime=None):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    if mtime is not None:
        os.utime(path, (mtime, mtime))


class Parking(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        self.step, self.kept = root / "step", root / "kept"
        self.files = {"run.part.h5": os.urandom(5000),
                      "checkpoints/lab-0-100.restart": bytes(range(256)) * 40,
                      "checkpoints/state.json": b'{"key": "k"}\n'}
        for i, (rel, data) in enumerate(self.files.items()):
            write(self.step / rel, data, mtime=1.7e9 + 100 * i + 0.25)

    def tearDown(self):
        self.tmp.cleanup()

    def test_park_and_unpark_give_the_files_back(self):
        written = step_archive.park(self.step, self.kept, list(self.files), {"step": 100})
        parked = self.kept / step_archive.PARKED
        record = json.loads((parked / step_archive.PARKED_RECORD).read_text())
        self.assertEqual(record["step"], 100)
        self.assertEqual([f["path"] for f in record["files"]], list(self.files))
        self.assertEqual(written, sum(f["xz_bytes"] for f in record["files"]))
        for f in record["files"]:  # each stored as xz, sizes recorded
            self.assertEqual(lzma.decompress((parked / f"{f['path']}.xz").read_bytes()),
                             self.files[f["path"]])
            self.assertEqual(f["bytes"], len(self.files[f["path"]]))
        self.assertFalse((self.step / ".parking").exists(), "staging folder left behind")
        new = Path(self.tmp.name) / "new_machine"
        self.assertEqual(step_archive.unpark(self.kept, new)["step"], 100)
        for i, (rel, data) in enumerate(self.files.items()):
            self.assertEqual((new / rel).read_bytes(), data)
            self.assertAlmostEqual((new / rel).stat().st_mtime, 1.7e9 + 100 * i + 0.25, places=5)

    def test_a_newer_park_replaces_the_older_one_whole(self):
        step_archive.park(self.step, self.kept, list(self.files), {"step": 100})
        write(self.step / "checkpoints/lab-0-200.restart", b"newer")
        step_archive.park(self.step, self.kept, ["checkpoints/lab-0-200.restart"], {"step": 200})
        parked = self.kept / step_archive.PARKED
        self.assertEqual(step_archive.parked(self.kept)["step"], 200)
        self.assertEqual(sorted(p.name for p in parked.rglob("*") if p.is_file()),
                         ["lab-0-200.restart.xz", "parked.json"])
        self.assertEqual(sorted(p.name for p in self.kept.iterdir()), ["parked"])

    def test_a_file_gone_before_it_is_linked_is_named_and_nothing_is_replaced(self):
        step_archive.park(self.step, self.kept, list(self.files), {"step": 100})
        with self.assertRaises(FileNotFoundError):
            step_archive.park(self.step, self.kept, ["checkpoints/lab-0-300.restart"],
                              {"step": 300})
        self.assertEqual(step_archive.parked(self.kept)["step"], 100)

    def test_a_linked_file_removed_while_parking_is_still_parked(self):
        removed = []

        def snapshot(src, dest):  # runs after the links: the step removes its checkpoint now
            (self.step / "checkpoints/lab-0-100.restart").unlink()
            removed.append(True)
            dest.write_bytes(Path(src).read_bytes())

        step_archive.park(self.step, self.kept, list(self.files), {"step": 100},
                          snapshot={"run.part.h5": snapshot})
        self.assertTrue(removed)
        new = Path(self.tmp.name) / "new_machine"
        step_archive.unpark(self.kept, new)
        self.assertEqual((new / "checkpoints/lab-0-100.restart").read_bytes(),
                         self.files["checkpoints/lab-0-100.restart"])

    def test_no_unpark_over_or_beside_a_finished_step(self):
        step_archive.park(self.step, self.kept, list(self.files), {"step": 100})
        done_here = Path(self.tmp.name) / "done_here"
        write(done_here / step_archive.DONE, b"{}")
        self.assertIsNone(step_archive.unpark(self.kept, done_here))
        self.assertFalse((done_here / "run.part.h5").exists())
        write(self.kept / step_archive.DONE, b"{}")  # finished since it was parked
        self.assertIsNone(step_archive.unpark(self.kept, Path(self.tmp.name) / "new"))

    def test_restore_and_keep_leave_the_parked_folder_alone_and_drop_removes_it(self):
        step_archive.park(self.step, self.kept, list(self.files), {"step": 100})
        write(self.step / step_archive.DONE, b'{"exit_status": 0}')
        step_archive.keep(self.step, self.kept)
        self.assertIsNotNone(step_archive.parked(self.kept))
        other = Path(self.tmp.name) / "other"
        self.assertTrue(step_archive.restore(self.kept, other))
        self.assertFalse((other / step_archive.PARKED).exists())
        step_archive.drop_parked(self.kept)
        self.assertIsNone(step_archive.parked(self.kept))
        self.assertFalse((self.kept / step_archive.PARKED).exists())

    def test_nothing_parked(self):
        self.assertIsNone(step_archive.parked(self.kept))
        self.assertIsNone(step_archive.unpark(self.kept, self.step))


if __name__ == "__main__":
    unittest.main()
