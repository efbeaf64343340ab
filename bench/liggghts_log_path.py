"""The benchmarks' one way to the shared parser of LIGGGHTS' screen output ("Loop time" lines and
thermo tables: postprocess/wheelsim_post/liggghts_log.py): puts postprocess/ on the path and
re-exports it."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "postprocess"))
from wheelsim_post import liggghts_log  # noqa: E402,F401
from wheelsim_post.liggghts_log import Loop, loops  # noqa: E402,F401
