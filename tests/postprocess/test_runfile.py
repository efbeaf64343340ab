"""wheelsim_post.runfile: written rows only, malformed observables, missing observables,
snapshots."""

import os
import unittest

import h5py
import numpy as np

import synthetic
from helpers import TempDirTestCase
from wheelsim_post.errors import PostError
from wheelsim_post.runfile import RunFile


class ObservableTest(TempDirTestCase):
    def test_rows_with_negative_step_are_dropped(self):
        path = self.path("crashed.h5")
        synthetic.write_rig_run(path, crashed=True)
        with RunFile(path) as run:
            dp = run.observable("drawbar_pull")
            raw = len(h5py.File(path, "r")["observables/drawbar_pull/step"])
        self.assertEqual(raw, 1306)  # 1301 written + 5 torn rows
        self.assertEqual(len(dp), 1301)
        self.assertTrue(np.all(dp.step >= 0))
        self.assertEqual(dp.unit, "N")

    def test_datasets_of_unequal_length_are_a_malformed_file(self):
        # the writer commits step, time and value together (hdf5-layout.md, "Crash
        # guarantees"): a value shorter than time is not a crash but a broken file
        path = self.path("torn.h5")
        with h5py.File(path, "w") as f:
            synthetic.write_header(f)
            synthetic.write_observable(
                f, "sinkage", [0, 1, 2], [0.0, 0.1, 0.2], [1, 2, 3], "m"
            )
            del f["observables/sinkage/value"]
            f["observables/sinkage"].create_dataset("value", data=[1.0, 2.0])
        with RunFile(path) as run, self.assertRaisesRegex(
            PostError,
            r"torn.h5': observable 'sinkage' has datasets of different lengths: "
            r"step 3, time 3, value 2 rows",
        ):
            run.observable("sinkage")

    def test_values_that_are_not_numbers_name_the_observable(self):
        path = self.path("text.h5")
        synthetic.write_rig_run(path)
        with h5py.File(path, "a") as f:
            group = f["observables/drawbar_pull"]
            rows = len(group["step"])
            del group["value"]
            group.create_dataset("value", data=["12.5"] * rows, dtype=synthetic.STRING)
        with RunFile(path) as run, self.assertRaisesRegex(
            PostError,
            r"text.h5': observable 'drawbar_pull': dataset 'value' holds strings, "
            r"expected numbers",
        ):
            run.observable("drawbar_pull")

    def test_nested_and_multi_component_observables(self):
        path = self.path("run.h5")
        synthetic.write_rig_run(path)
        with RunFile(path) as run:
            pos = run.observable("wheel/position")
            self.assertIn("wheel/position", run.observable_names())
        self.assertEqual(pos.value.shape, (1301, 3))

    def test_missing_observable_names_file_and_observable(self):
        path = self.path("run.h5")
        synthetic.write_rig_run(path, omit=("sinkage",))
        with RunFile(path) as run, self.assertRaises(PostError) as ctx:
            run.observable("sinkage")
        self.assertIn("run.h5", str(ctx.exception))
        self.assertIn("no observable 'sinkage'", str(ctx.exception))

    def test_missing_and_non_hdf5_files(self):
        with self.assertRaisesRegex(PostError, "does not exist"):
            RunFile(self.path("nope.h5"))
        bad = self.path("text.h5")
        with open(bad, "w") as f:
            f.write("not hdf5")
        with self.assertRaisesRegex(PostError, "cannot open run file .*text.h5"):
            RunFile(bad)
        os.mkdir(self.path("dir.h5"))
        with self.assertRaisesRegex(PostError, "run file .*dir.h5' is a directory"):
            RunFile(self.path("dir.h5"))


class SnapshotTest(TempDirTestCase):
    def test_snapshot_fields_steps_and_grid(self):
        path = self.path("scm.h5")
        with h5py.File(path, "w") as f:
            synthetic.write_header(f)
            value = np.arange(12.0).reshape(3, 4)
            for step in (200, 100):
                synthetic.write_snapshot(
                    f, "sinkage", step, step * 1e-3, value, "m", 1.0, -0.5, 0.1
                )
        with RunFile(path) as run:
            self.assertEqual(run.snapshot_fields(), ["sinkage"])
            self.assertEqual(run.snapshot_steps("sinkage"), [100, 200])
            snap = run.snapshot("sinkage", 200)
            with self.assertRaisesRegex(
                PostError, "no snapshot '/terrain/sinkage/000000300'"
            ):
                run.snapshot("sinkage", 300)
        self.assertEqual(snap.step, 200)
        self.assertAlmostEqual(snap.time, 0.2)
        # columns x = 1.0 .. 1.3, rows y = -0.5 .. -0.3, cells centred on the grid points
        np.testing.assert_allclose(snap.extent(), (0.95, 1.35, -0.55, -0.25))

    def test_a_grid_spacing_not_above_0_or_a_nan_origin_names_the_snapshot(self):
        path = self.path("scm.h5")
        with h5py.File(path, "w") as f:
            synthetic.write_header(f)
            for step, x0, spacing in ((100, 0.0, 0.0), (200, 0.0, -0.1),
                                      (300, 0.0, float("nan")), (400, float("nan"), 0.1)):
                synthetic.write_snapshot(f, "height", step, 0.1, np.ones((2, 3)), "m",
                                         x0, 0.0, spacing)
        with RunFile(path) as run:
            for step, text in ((100, "spacing 0 m"), (200, "spacing -0.1 m"),
                               (300, "spacing nan m"), (400, "x0 nan m")):
                with self.subTest(step=step), self.assertRaisesRegex(
                    PostError, f"scm.h5': snapshot '/terrain/height/{step:09d}' has {text}"
                ):
                    run.snapshot("height", step)


if __name__ == "__main__":
    unittest.main()
